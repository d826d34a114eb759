//! The data form in the window while `time` runs: whether a scene's parts follow it, and how
//! fine a grid each moment's pre-pass can afford.

use sdfc_compiler::check::TIME;
use sdfc_compiler::lower::tracer::Options;
use sdfc_compiler::scene::Scene;
use std::time::Duration;

/// Whether `scene`, drawn with `options`, is in the data form with parts that move with `time`.
pub(super) fn follows_time(scene: &Scene, options: &Options) -> bool {
    options.form == sdfc_compiler::lower::tracer::Form::Data
        && sdfc_compiler::tape::data::follows(scene)
            .into_iter()
            .any(|i| scene.params[i].name == TIME)
}

/// What the pre-pass may take for each moment of a running `time` (the window then makes its
/// grid coarser: the trace slows less than the pre-pass speeds up).
const ANIMATED_PREPASS: Duration = Duration::from_millis(40);

/// The cells a side for the next moment, after `used` (`None`: the parts' own count, `full`)
/// took `took`: scaled so that the next pre-pass takes about [`ANIMATED_PREPASS`] (its work
/// grows with the cells, as the cube of the side), within 8 and `full`.
pub(super) fn next_cells(used: Option<usize>, full: usize, took: Duration) -> Option<usize> {
    let side = used.unwrap_or(full) as f64;
    let ratio = ANIMATED_PREPASS.as_secs_f64() / took.as_secs_f64().max(1e-6);
    let next = (side * ratio.cbrt()).round() as usize;
    // (`--cells` may be below the usual least: then it is the least too.)
    Some(next.clamp(sdfc_compiler::tape::data::CELLS.0.min(full), full))
}

/// The most cells a side a running `time`'s grid takes for `scene` drawn with `options`:
/// `--cells`, else those its parts call for (`tape::data::cells_for`); 0 where `time` moves
/// none of its parts (no grid is made again).
pub(super) fn animated_cells(scene: &Scene, options: &Options) -> usize {
    if !follows_time(scene, options) {
        return 0;
    }
    options.cells.unwrap_or_else(|| {
        sdfc_compiler::tape::build(scene).map_or(1, |tree| {
            sdfc_compiler::tape::data::cells_for(tree.leaves())
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_slow_pre_pass_makes_the_next_grid_coarser() {
        // 400 ms at 64 a side: ten times the budget, so 64 / 10^(1/3) = 30 next.
        assert_eq!(next_cells(None, 64, Duration::from_millis(400)), Some(30));
        // Fast enough: back towards the parts' own count, never above it or below 8.
        assert_eq!(next_cells(Some(30), 64, Duration::from_millis(5)), Some(60));
        assert_eq!(next_cells(Some(60), 64, Duration::from_millis(1)), Some(64));
        assert_eq!(next_cells(Some(8), 64, Duration::from_secs(10)), Some(8));
        // `--cells 4`: never more than 4, and no panic for a least above the most.
        assert_eq!(next_cells(Some(4), 4, Duration::from_secs(10)), Some(4));
        assert_eq!(next_cells(Some(4), 4, Duration::from_millis(1)), Some(4));
    }
}
