//! Module-scope declarations the interfaces share: named struct types and bound globals.

use crate::ir::builder::ModuleBuilder;
use crate::layout;
use naga::{AddressSpace, Handle, ResourceBinding, Span, StructMember, Type, TypeInner};

/// The struct type `name` of `members` (name, type, byte offset), `span` bytes long.
pub(super) fn struct_ty(
    mb: &mut ModuleBuilder,
    name: &str,
    members: &[(&str, Handle<Type>, u32)],
    span: u32,
) -> Handle<Type> {
    let members = members
        .iter()
        .map(|&(n, ty, offset)| StructMember {
            name: Some(n.to_string()),
            ty,
            binding: None,
            offset,
        })
        .collect();
    mb.named_ty(name, TypeInner::Struct { members, span })
}

/// The global `name` of type `ty` in `space`, bound at `binding` in the interface's group.
pub(super) fn global(
    mb: &mut ModuleBuilder,
    name: &str,
    ty: Handle<Type>,
    space: AddressSpace,
    binding: u32,
) -> Handle<naga::GlobalVariable> {
    mb.module.global_variables.append(
        naga::GlobalVariable {
            name: Some(name.to_string()),
            space,
            binding: Some(ResourceBinding {
                group: layout::GROUP,
                binding,
            }),
            ty,
            init: None,
            memory_decorations: naga::MemoryDecorations::empty(),
        },
        Span::UNDEFINED,
    )
}
