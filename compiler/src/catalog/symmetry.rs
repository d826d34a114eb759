//! The symmetry rules of operators: which reflections across coordinate planes and exchanges
//! of coordinates (`Operator::mirror`, `Operator::swap`) a result keeps from its children.

use super::Ctx;
use glam::DVec3;

/// No exchange symmetry known (see [`Primitive::swap`]): the rule of every entry that does not
/// state one.
pub(crate) const NO_SWAP: fn(&Ctx) -> [bool; 3] = |_| [false; 3];

/// Per axis k, whether `v`'s two other components are equal: the exchange symmetries of a field
/// whose only dependence on direction is `v` (a box's size, a plane's normal, a move).
pub(crate) fn equal_pairs(v: DVec3) -> [bool; 3] {
    [v.y == v.z, v.x == v.z, v.x == v.y]
}

/// The child's symmetry (operators that act the same on x and −x).
pub(super) const CHILD: fn(&Ctx) -> [bool; 3] = |c| c.child_mirror[0];
/// Symmetric where every child is.
pub(super) const EVERY: fn(&Ctx) -> [bool; 3] = |c| all_of(&c.child_mirror);
/// Exchange symmetric where every child is.
pub(super) const SWAP_EVERY: fn(&Ctx) -> [bool; 3] = |c| all_of(&c.child_swap);
/// The child's exchange symmetry.
pub(super) const SWAP_CHILD: fn(&Ctx) -> [bool; 3] = |c| c.child_swap[0];
/// Not known to be symmetric.
pub(super) const NONE: fn(&Ctx) -> [bool; 3] = |_| [false; 3];

/// A rotation about a coordinate axis keeps the symmetry along that axis (the two commute); a
/// quarter or half turn about it also keeps the other two where the child has both (the
/// reflected result is the child turned by −θ, the same as by θ once the child is invariant under
/// the half turn 2θ = π, or any multiple of it). Otherwise: not known.
fn quarter_turned_mirror(c: &Ctx) -> [bool; 3] {
    let (axis, angle, child) = (c.vec(0), c.num(1), c.child_mirror[0]);
    let quarters = angle / std::f64::consts::FRAC_PI_2;
    let whole = (quarters - quarters.round()).abs() < 1e-9;
    if whole && quarters.round().rem_euclid(4.0) == 0.0 {
        return child;
    }
    let Some(k) = (0..3).find(|&k| axis[k].abs() == 1.0) else {
        return [false; 3];
    };
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    let others = whole && child[i] && child[j];
    let mut m = [others; 3];
    m[k] = child[k];
    m
}

/// Whether `angle` is a whole number of eighth turns, and how many (mod 8).
fn eighths(angle: f64) -> Option<i64> {
    let e = angle / std::f64::consts::FRAC_PI_4;
    ((e - e.round()).abs() < 1e-9).then(|| (e.round() as i64).rem_euclid(8))
}

/// The reflections of a turned child where its eighth-turn symmetry gives more than
/// [`quarter_turned_mirror`]: a child symmetric under both reflections across the axis and the
/// exchange of their coordinates (a square about the axis: the symmetries of a square) keeps all
/// three after any whole number of eighth turns about that axis, since an eighth turn maps the
/// square's four mirror lines onto each other.
pub(super) fn rotated_mirror(c: &Ctx) -> [bool; 3] {
    let by_quarters = quarter_turned_mirror(c);
    match square_about(c) {
        Some(k) => {
            let mut m = [true; 3];
            m[k] = c.child_mirror[0][k];
            m
        }
        None => by_quarters,
    }
}

/// The axis k of a turn by a whole number of eighth turns about a coordinate axis, when the
/// child has the symmetries of a square about k (reflections of both other coordinates and their
/// exchange).
fn square_about(c: &Ctx) -> Option<usize> {
    let (axis, child, swap) = (c.vec(0), c.child_mirror[0], c.child_swap[0]);
    eighths(c.num(1))?;
    let k = (0..3).find(|&k| axis[k].abs() == 1.0)?;
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    (child[i] && child[j] && swap[k]).then_some(k)
}

/// The exchange symmetries of a turned child: all the child's after a whole number of turns;
/// about a coordinate axis k, the child's exchange about k after a half turn (which maps
/// (x, y) to (−x, −y) and commutes with the exchange) or any eighth turn of a square (see
/// [`rotated_mirror`]); none otherwise.
pub(super) fn rotated_swap(c: &Ctx) -> [bool; 3] {
    let Some(e) = eighths(c.num(1)) else {
        return [false; 3];
    };
    if e == 0 {
        return c.child_swap[0];
    }
    let mut out = [false; 3];
    if let Some(k) = (0..3).find(|&k| c.vec(0)[k].abs() == 1.0) {
        out[k] = c.child_swap[0][k] && (e == 4 || square_about(c).is_some());
    }
    out
}

/// Per axis, both.
pub(super) fn and(a: [bool; 3], b: [bool; 3]) -> [bool; 3] {
    all_of(&[a, b])
}

/// Per axis, whether every one of `flags` has it.
fn all_of(flags: &[[bool; 3]]) -> [bool; 3] {
    [0, 1, 2].map(|i| flags.iter().all(|m| m[i]))
}
