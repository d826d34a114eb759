//! The compiler's integration tests as one binary (as naga's `tests/naga/main.rs`): each file
//! of this folder is a module, its tests named `<file>::<test>`; the helpers they share are this
//! crate's library (`lib.rs`).

mod bake;
mod converge;
mod emit;
mod errors;
mod eval;
mod examples;
mod fuzz;
mod fuzz_scenes;
mod house;
mod imports;
mod interface;
mod limits;
mod lipschitz;
mod lipschitz_cases;
mod lipschitz_params;
mod lipschitz_sampler;
mod literals;
mod mesh;
mod tape;
mod tape_data;
mod tidy;
