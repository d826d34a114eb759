//! Baked volumes in the module: per volume of `Scene::volumes`, a `texture_3d<f32>` bound at
//! `layout::VOLUME_BINDING + i` and its read function `volume_<i>(p)` (`catalog/gpu/baked.rs`);
//! nothing in a scene without `bake`.

use crate::ir::{FnBuilder, ModuleBuilder};
use crate::layout;
use crate::scene::Scene;
use naga::{AddressSpace, ImageClass, ImageDimension, ScalarKind, TypeInner};

/// Declares every volume's texture and read function.
pub(super) fn add(mb: &mut ModuleBuilder, scene: &Scene) {
    let volumes = scene.volumes();
    if volumes.is_empty() {
        return;
    }
    let image = mb.ty(TypeInner::Image {
        dim: ImageDimension::D3,
        arrayed: false,
        class: ImageClass::Sampled {
            kind: ScalarKind::Float,
            multi: false,
        },
    });
    for (i, volume) in volumes.into_iter().enumerate() {
        let texture = super::globals::global(
            mb,
            &format!("volume_{i}_texels"),
            image,
            AddressSpace::Handle,
            layout::VOLUME_BINDING + i as u32,
        );
        let v3 = mb.vec3();
        let f32t = mb.f32();
        let mut b = FnBuilder::new(mb, &format!("volume_{i}_at"), &[("p", v3)], Some(f32t));
        let d = crate::catalog::gpu::baked::read(&mut b, &volume, texture);
        b.ret(Some(d));
        let f = b.finish();
        let h = mb.add_function(f);
        mb.volumes.push((volume, h));
    }
}
