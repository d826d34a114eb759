//! What the library entry offers a host besides its functions: a named constant per material.

use crate::ir::builder::ModuleBuilder;
use crate::scene::Scene;
use naga::{Constant, Expression, Literal, Span};

/// The prefix of a material's constant: `MATERIAL_gold` is gold's id in `map_material`'s
/// results (0 is the default material).
pub const MATERIAL_CONSTANT: &str = "MATERIAL_";

/// A name from the scene as the shader spells it, so that the back ends keep it as it is: `_`
/// after a name that ends in a digit (naga's namer would add it, as its numbering suffixes
/// end in digits) or is a WGSL reserved word or built-in (`loop` → `loop_`). Another
/// language's reserved word may still get a `_` from that back end (docs/interface.md).
pub fn shader_name(name: &str) -> String {
    // naga's namer first collapses runs of `_` and drops trailing ones (`r_` → `r`).
    let mut base = String::with_capacity(name.len());
    for c in name.chars() {
        if !(c == '_' && base.ends_with('_')) {
            base.push(c);
        }
    }
    let base = base.trim_end_matches('_');
    let reserved = naga::keywords::wgsl::RESERVED.contains(&base)
        || naga::keywords::wgsl::BUILTIN_IDENTIFIERS.contains(&base);
    if base.ends_with(|c: char| c.is_ascii_digit()) || reserved {
        format!("{base}_")
    } else {
        base.to_string()
    }
}

/// The constant that names material `name`'s id.
pub fn material_constant(name: &str) -> String {
    shader_name(&format!("{MATERIAL_CONSTANT}{name}"))
}

/// `const MATERIAL_<name>: u32 = id;` for each declared material.
pub(super) fn add_material_constants(mb: &mut ModuleBuilder, scene: &Scene) {
    let u = mb.u32();
    for (i, m) in scene.materials.iter().enumerate() {
        let init = mb.module.global_expressions.append(
            Expression::Literal(Literal::U32(i as u32 + 1)),
            Span::UNDEFINED,
        );
        mb.module.constants.append(
            Constant {
                name: Some(material_constant(&m.name)),
                ty: u,
                init,
            },
            Span::UNDEFINED,
        );
    }
}
