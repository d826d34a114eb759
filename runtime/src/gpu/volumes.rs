//! Baked volumes on the device: each `bake` map an `r32float` 3D texture, uploaded once and
//! bound at `layout::VOLUME_BINDING + i` in every module that declares volume i.

use super::{Error, Gpu, lock};
use sdfc_compiler::bake::Volume;
use sdfc_compiler::layout::{GROUP, MAX_VOLUMES, VOLUME_BINDING};
use std::sync::Arc;

/// A volume and its texture.
pub(crate) struct OnDevice {
    volume: Arc<Volume>,
    view: wgpu::TextureView,
}

impl Gpu {
    /// Sets what the modules of `scene` prepared from now on read besides their outputs: its
    /// parameters' values ([`Gpu::set_params`]) and its baked volumes ([`Gpu::set_volumes`]).
    pub fn set_scene(&self, scene: &sdfc_compiler::scene::Scene) {
        self.set_params(&sdfc_compiler::lower::params::bytes(&scene.params));
        self.set_volumes(&scene.volumes());
    }

    /// Sets the baked volumes (`Scene::volumes`, in that order) the modules prepared from now
    /// on read; a volume already on the device (the same `Arc`) is not uploaded again.
    pub fn set_volumes(&self, volumes: &[Arc<Volume>]) {
        let mut on = lock(&self.volumes);
        let mut next = Vec::with_capacity(volumes.len());
        for v in volumes {
            match on.iter().position(|o| Arc::ptr_eq(&o.volume, v)) {
                Some(at) => next.push(on.swap_remove(at)),
                None => next.push(self.upload(v)),
            }
        }
        *on = next;
    }

    fn upload(&self, volume: &Arc<Volume>) -> OnDevice {
        let [nx, ny, nz] = volume.grid.n.map(|n| n as u32);
        let size = wgpu::Extent3d {
            width: nx,
            height: ny,
            depth_or_array_layers: nz,
        };
        let texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("baked volume"),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D3,
            format: wgpu::TextureFormat::R32Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        self.queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            &sdfc_compiler::bake::file::raw(volume),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4 * nx),
                rows_per_image: Some(ny),
            },
            size,
        );
        OnDevice {
            volume: volume.clone(),
            view: texture.create_view(&Default::default()),
        }
    }

    /// The texture views `module` reads, with their bindings: an internal error when it
    /// declares a volume that was not set.
    pub(crate) fn volume_views(
        &self,
        module: &naga::Module,
    ) -> Result<Vec<(u32, wgpu::TextureView)>, Error> {
        let on = lock(&self.volumes);
        let mut out = Vec::new();
        for (_, g) in module.global_variables.iter() {
            let Some(b) = g.binding else { continue };
            let index = b.binding.wrapping_sub(VOLUME_BINDING) as usize;
            if b.group != GROUP || index >= MAX_VOLUMES {
                continue;
            }
            let o = on.get(index).ok_or(Error::Volumes {
                index,
                set: on.len(),
            })?;
            out.push((b.binding, o.view.clone()));
        }
        Ok(out)
    }
}
