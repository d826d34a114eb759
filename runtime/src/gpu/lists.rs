//! The list entries of the tests: rays traced, or the field evaluated at points, in one
//! dispatch (input and output at `sdfc_compiler::layout::LIST_BINDINGS`).

use super::{Error, Gpu};
use sdfc_compiler::layout::{GROUP, LIST_BINDINGS, LIST_STRIDE};

/// A list entry's module and its compiled pipeline.
pub struct ListProgram {
    module: naga::Module,
    pipeline: wgpu::ComputePipeline,
}

impl Gpu {
    /// Traces a list of rays with a module compiled for `Entry::Rays`: each ray is an origin,
    /// a direction and the pixel footprint (for ε `pixel`); returns (t, steps, flags) per ray.
    pub fn trace_rays(
        &self,
        module: &naga::Module,
        rays: &[([f32; 3], [f32; 3], f32)],
    ) -> Result<Vec<(f32, u32, u32)>, Error> {
        Ok(self
            .trace_rays_full(module, rays)?
            .iter()
            .map(|v| (v[0], v[1] as u32, v[2] as u32))
            .collect())
    }

    /// [`Gpu::trace_rays`] with the whole `vec4(t, steps, flags, cover)` per ray.
    pub fn trace_rays_full(
        &self,
        module: &naga::Module,
        rays: &[([f32; 3], [f32; 3], f32)],
    ) -> Result<Vec<[f32; 4]>, Error> {
        let input: Vec<f32> = rays
            .iter()
            .flat_map(|(o, d, px)| [o[0], o[1], o[2], *px, d[0], d[1], d[2], 0.0])
            .collect();
        let groups = (rays.len() as u32).div_ceil(sdfc_compiler::layout::RAYS_WORKGROUP);
        let program = self.list_program(module);
        self.run_list(&program, ("rays", "hits"), &input, rays.len(), groups)
    }

    /// Evaluates the scene's field at a list of points with a module compiled for
    /// `Entry::Field`, in one dispatch: `map(p)` (the distance bound, already divided by the
    /// root's λ) per point.
    pub fn eval_points(
        &self,
        module: &naga::Module,
        points: &[[f32; 3]],
    ) -> Result<Vec<f32>, Error> {
        self.eval_points_with(&self.list_program(module), points)
    }

    /// A list entry's pipeline, compiled once for many dispatches ([`Gpu::eval_points_with`]).
    pub fn list_program(&self, module: &naga::Module) -> ListProgram {
        ListProgram {
            module: module.clone(),
            pipeline: self.pipeline(module),
        }
    }

    /// [`Gpu::eval_points`] with a pipeline already compiled (from a module for
    /// `Entry::Field`).
    pub fn eval_points_with(
        &self,
        program: &ListProgram,
        points: &[[f32; 3]],
    ) -> Result<Vec<f32>, Error> {
        let input: Vec<f32> = points
            .iter()
            .flat_map(|p| [p[0], p[1], p[2], 0.0])
            .collect();
        let groups = (points.len() as u32).div_ceil(sdfc_compiler::layout::FIELD_WORKGROUP);
        let out = self.run_list(program, ("points", "values"), &input, points.len(), groups)?;
        Ok(out.iter().map(|v| v[0]).collect())
    }

    /// Runs a list entry (`LIST_BINDINGS`: `input`, read only, then one vec4 of output per
    /// item) in one dispatch of `groups` workgroups and reads the output back.
    fn run_list(
        &self,
        program: &ListProgram,
        (input_label, output_label): (&str, &str),
        input: &[f32],
        items: usize,
        groups: u32,
    ) -> Result<Vec<[f32; 4]>, Error> {
        if items == 0 {
            return Ok(Vec::new());
        }
        let device = &self.device;
        let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let (module, pipeline) = (&program.module, &program.pipeline);
        let bytes: Vec<u8> = input.iter().copied().flat_map(f32::to_le_bytes).collect();
        let input_buf = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(input_label),
            size: bytes.len() as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        self.queue.write_buffer(&input_buf, 0, &bytes);
        let size = items as u64 * LIST_STRIDE;
        let output = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(output_label),
            size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let params = self.params_buffer(module)?;
        let mut entries = vec![
            wgpu::BindGroupEntry {
                binding: LIST_BINDINGS[0],
                resource: input_buf.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: LIST_BINDINGS[1],
                resource: output.as_entire_binding(),
            },
        ];
        if let Some((buffer, binding)) = &params {
            entries.push(wgpu::BindGroupEntry {
                binding: *binding,
                resource: buffer.as_entire_binding(),
            });
        }
        let tape = self.tape_buffers(super::tape::reads_tape(module));
        for (binding, buffer) in &tape {
            entries.push(wgpu::BindGroupEntry {
                binding: *binding,
                resource: buffer.as_entire_binding(),
            });
        }
        let volumes = self.volume_views(module)?;
        for (binding, view) in &volumes {
            entries.push(wgpu::BindGroupEntry {
                binding: *binding,
                resource: wgpu::BindingResource::TextureView(view),
            });
        }
        let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(input_label),
            layout: &pipeline.get_bind_group_layout(GROUP),
            entries: &entries,
        });
        let mut enc = device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            pass.set_pipeline(pipeline);
            pass.set_bind_group(GROUP, &bind, &[]);
            pass.dispatch_workgroups(groups, 1, 1);
        }
        self.queue.submit([enc.finish()]);
        self.wait()?;
        if let Some(e) = pollster::block_on(validation.pop()) {
            return Err(Error::InvalidListModule(e.to_string()));
        }
        let bytes = self.read(&output, size)?;
        Ok(bytes
            .chunks_exact(LIST_STRIDE as usize)
            .map(|c| {
                let f = |i: usize| f32::from_le_bytes(c[i * 4..i * 4 + 4].try_into().unwrap());
                [f(0), f(1), f(2), f(3)]
            })
            .collect())
    }
}
