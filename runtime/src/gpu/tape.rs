//! The data form's buffers on the device (issue 33): the table of parts, the cells' programs
//! and their ranges (`sdfc_compiler::tape::data`), bound at `layout::TAPE_BINDINGS` in every module that
//! declares them (compiled with `Form::Data`).

use super::{Gpu, lock};
use sdfc_compiler::layout::{GROUP, TAPE_BINDINGS};
use sdfc_compiler::tape::data::Data;
use wgpu::util::DeviceExt;

impl Gpu {
    /// Sets the data form's buffers the modules prepared from now on read (`None`: none).
    pub fn set_tape(&self, data: Option<&Data>) {
        let buffers = data.map(|d| {
            let [nodes, code, ranges] = d.buffers();
            let make = |label: &str, contents: Vec<u8>| {
                self.device
                    .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: Some(label),
                        contents: &contents,
                        usage: wgpu::BufferUsages::STORAGE,
                    })
            };
            [
                make("tape nodes", nodes),
                make("tape code", code),
                make("tape ranges", ranges),
            ]
        });
        *lock(&self.tape) = buffers;
    }

    /// The data form's buffers `module` reads, with their bindings (none where it declares
    /// none; an empty list where it does and none were set, which the bind group then refuses
    /// as an internal error).
    pub(crate) fn tape_buffers(&self, module: &naga::Module) -> Vec<(u32, wgpu::Buffer)> {
        let declared = module.global_variables.iter().any(|(_, g)| {
            g.binding
                .is_some_and(|b| b.group == GROUP && b.binding == TAPE_BINDINGS[0])
        });
        match (&*lock(&self.tape), declared) {
            (Some(buffers), true) => TAPE_BINDINGS
                .into_iter()
                .zip(buffers.iter().cloned())
                .collect(),
            _ => Vec::new(),
        }
    }
}
