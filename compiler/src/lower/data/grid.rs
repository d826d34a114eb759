//! Where a point lies in the data form's grid: the cell's range of the program (the grid read
//! from the ranges buffer's header, `tape::data::HEADER`), and the proxy outside it.

use crate::ir::{Ex, FnBuilder};
use crate::tape::data::Layout;
use naga::ScalarKind;

/// The grid as the ranges buffer's header gives it (`tape::data::HEADER`): its lowest corner,
/// cell size, cells along x, y and z (as floats and as u32s) and the proxy's margin.
pub(super) struct Grid {
    lo: Ex,
    /// The cells' edge.
    pub size: Ex,
    n: Ex,
    counts: [Ex; 3],
    margin: Ex,
}

/// Reads the grid from the header of `ranges`.
fn grid(b: &mut FnBuilder, ranges: Ex) -> Grid {
    let mut h = Vec::with_capacity(4);
    for k in 0..crate::tape::data::HEADER as u32 {
        let i = b.u(k);
        let ptr = b.index(ranges, i);
        h.push(b.load(ptr));
    }
    let float = |b: &mut FnBuilder, v: Ex, c: u32| {
        let x = b.at(v, c);
        b.bitcast(x, ScalarKind::Float)
    };
    let (x, y, z) = (float(b, h[0], 0), float(b, h[0], 1), float(b, h[1], 0));
    let lo = b.compose_vec3([x, y, z]);
    let size = float(b, h[1], 1);
    let counts = [b.at(h[2], 0), b.at(h[2], 1), b.at(h[3], 0)];
    let n = counts.map(|c| b.cast(c, ScalarKind::Float));
    let n = b.compose_vec3(n);
    let margin = float(b, h[3], 1);
    Grid {
        lo,
        size,
        n,
        counts,
        margin,
    }
}

/// The distance from `p` to the grid's box plus its margin: outside it, a distance bound for
/// the parts the grid holds (they lie the margin inside it: `tape::data::Layout::proxy`).
pub(super) fn proxy(b: &mut FnBuilder, g: &Grid, p: Ex) -> Ex {
    let half = b.f(0.5);
    let extent = b.mul(g.n, g.size);
    let half = b.mul(extent, half);
    let center = b.add(g.lo, half);
    let rel = b.sub(p, center);
    let d = crate::catalog::gpu::prims::box_half(b, rel, half);
    b.add(d, g.margin)
}

/// The range (first instruction, count) of the cell holding `p`, the last range where the
/// grid does not; and whether it does (none where the scene has no grid), with the grid.
pub(super) fn cell_range(
    b: &mut FnBuilder,
    layout: &Layout,
    ranges: Ex,
    p: Ex,
) -> (Ex, Option<(Ex, Grid)>) {
    let header = crate::tape::data::HEADER as u32;
    if layout.n.iter().product::<usize>() == 0 {
        let at = b.u(header);
        let ptr = b.index(ranges, at);
        return (b.load(ptr), None);
    }
    let g = grid(b, ranges);
    let rel = b.sub(p, g.lo);
    let size = b.splat(g.size, naga::VectorSize::Tri);
    let rel = b.div(rel, size);
    let c = b.math(naga::MathFunction::Floor, &[rel]);
    let zero = b.splat3(0.0);
    let above = b.bin(naga::BinaryOperator::GreaterEqual, c, zero);
    let below = b.bin(naga::BinaryOperator::Less, c, g.n);
    let above = b.expr(naga::Expression::Relational {
        fun: naga::RelationalFunction::All,
        argument: above,
    });
    let below = b.expr(naga::Expression::Relational {
        fun: naga::RelationalFunction::All,
        argument: below,
    });
    let inside = b.bin(naga::BinaryOperator::LogicalAnd, above, below);
    // (Clamped before the conversion: a point far outside would not fit a u32.)
    let one = b.splat3(1.0);
    let top = b.sub(g.n, one);
    let c = b.clamp(c, zero, top);
    let c = b.cast(c, ScalarKind::Uint);
    let [x, y, z] = b.xyz(c);
    let [nx, ny, nz] = g.counts;
    let zy = b.mul(z, ny);
    let zy = b.add(zy, y);
    let zyx = b.mul(zy, nx);
    let index = b.add(zyx, x);
    let first = b.u(header);
    let index = b.add(index, first);
    let cells = b.mul(nx, ny);
    let cells = b.mul(cells, nz);
    let total = b.add(cells, first);
    let index = b.select(inside, index, total);
    let ptr = b.index(ranges, index);
    (b.load(ptr), Some((inside, g)))
}

/// A range's program length from its count (`tape::data::FAR`: a far cell's count holds its
/// clearance above the length).
pub(super) fn length(b: &mut FnBuilder, count: Ex) -> Ex {
    let far = b.u(crate::tape::data::FAR);
    let bit = b.bin(naga::BinaryOperator::And, count, far);
    let zero = b.u(0);
    let is_far = b.bin(naga::BinaryOperator::NotEqual, bit, zero);
    let mask = b.u(crate::tape::data::FAR_LENGTH);
    let short = b.bin(naga::BinaryOperator::And, count, mask);
    b.select(is_far, short, count)
}
