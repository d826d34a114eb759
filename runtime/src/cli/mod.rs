//! The command line's lowest layer: its definition (`args`, `values`, `tracer`), how messages
//! reach the user (`messages`), and reading and checking a scene file (`input`). The
//! subcommands (`crate::cmd`) and the viewer (`crate::view`) are built on it.

mod args;
pub mod driver;
mod error;
pub mod input;
pub mod messages;
mod tape;
pub mod tracer;
pub mod values;

pub use args::*;
pub use error::{Error, write_file};
pub use tape::{pruner, set_tape, tape_data};
