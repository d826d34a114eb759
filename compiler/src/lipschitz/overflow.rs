//! Where an `implicit`'s f32 arithmetic overflows: the value ranges of its parts over the
//! region rays reach, against f32's largest finite value.

use super::grad;
use crate::interval::Interval;
use crate::scene::Field;
use crate::syntax::BinOp;

/// The innermost part of `field` whose value may pass f32's range (±3.4e38) somewhere in
/// `region` — where the shader's f32 arithmetic gives an infinity, and NaN from ∞ − ∞, ∞/∞
/// or 0·∞ downstream — with what it is and its value range there. The f64 checker's own
/// domain errors (division by zero and the like) are `infer`'s; parameters without a range
/// have no bound to check and are left alone (their parts are not reported).
pub fn may_overflow(field: &Field, region: &[Interval; 3]) -> Option<(String, Interval)> {
    let mut unranged = false;
    field.params(&mut |r| unranged |= !r.ranged());
    if unranged {
        return None;
    }
    innermost(field, region)
}

fn innermost(field: &Field, region: &[Interval; 3]) -> Option<(String, Interval)> {
    let parts: Vec<&Field> = match field {
        Field::Neg(a) => vec![a],
        Field::Binary(_, a, b) => vec![a, b],
        Field::Call(_, args) => args.iter().collect(),
        Field::Const(_) | Field::Coord(_) | Field::Param(_) => vec![],
    };
    if let Some(found) = parts.into_iter().find_map(|p| innermost(p, region)) {
        return Some(found);
    }
    let (v, _) = grad(field, region, &mut None, &mut false);
    let max = f64::from(f32::MAX);
    // (Infinite both ways is interval arithmetic saying nothing — a power it does not bound, a
    // quotient by a range through 0, which `infer` reports — not a value found to be large.)
    let unknown = v.lo == f64::NEG_INFINITY && v.hi == f64::INFINITY;
    (!unknown && (v.hi > max || v.lo < -max)).then(|| (describe(field), v))
}

/// A part as a message names it.
fn describe(field: &Field) -> String {
    match field {
        Field::Call(f, _) => format!("`{}(…)`", f.name),
        Field::Binary(op, _, _) => match op {
            BinOp::Add => "a sum".to_string(),
            BinOp::Sub => "a difference".to_string(),
            BinOp::Mul => "a product".to_string(),
            BinOp::Div => "a quotient".to_string(),
            BinOp::Pow => "a power (`^`)".to_string(),
        },
        Field::Neg(_) => "a negation".to_string(),
        Field::Const(_) | Field::Coord(_) | Field::Param(_) => "a value".to_string(),
    }
}
