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

    /// The data form's buffers with their bindings, for a module that reads them (`reads`,
    /// [`reads_tape`]): none where it does not; an empty list where it does and none were set,
    /// which the bind group then refuses as an internal error.
    pub(crate) fn tape_buffers(&self, reads: bool) -> Vec<(u32, wgpu::Buffer)> {
        match (&*lock(&self.tape), reads) {
            (Some(buffers), true) => TAPE_BINDINGS
                .into_iter()
                .zip(buffers.iter().cloned())
                .collect(),
            _ => Vec::new(),
        }
    }
}

/// Whether `module` declares the data form's buffers (compiled with `Form::Data`).
pub(crate) fn reads_tape(module: &naga::Module) -> bool {
    module.global_variables.iter().any(|(_, g)| {
        g.binding
            .is_some_and(|b| b.group == GROUP && b.binding == TAPE_BINDINGS[0])
    })
}
