//! The data form's buffers on the device (issue 33): the table of parts, the cells' programs
//! and their ranges (`sdfc_compiler::tape::data`), bound at `layout::TAPE_BINDINGS` in every module that
//! declares them (compiled with `Form::Data`).

use super::{Error, Gpu, lock};
use sdfc_compiler::layout::{GROUP, TAPE_BINDINGS};
use sdfc_compiler::tape::data::Data;
use wgpu::util::DeviceExt;

impl Gpu {
    /// Sets the data form's buffers the modules prepared from now on read (`None`: none); an
    /// error where one is larger than the device binds.
    pub fn set_tape(&self, data: Option<&Data>) -> Result<(), Error> {
        let limit = self
            .limits
            .max_storage_buffer_binding_size
            .min(self.limits.max_buffer_size);
        let made = data.map(Data::buffers);
        let largest = made.iter().flatten().map(|b| b.len() as u64).max();
        if let Some(bytes) = largest.filter(|&b| b > limit) {
            return Err(Error::TapeTooLarge { bytes, limit });
        }
        let buffers = made.map(|[nodes, code, ranges]| {
            let make = |label: &str, contents: Vec<u8>| {
                self.device
                    .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: Some(label),
                        contents: &contents,
                        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                    })
            };
            [
                make("tape nodes", nodes),
                make("tape code", code),
                make("tape ranges", ranges),
            ]
        });
        *lock(&self.tape) = buffers;
        Ok(())
    }

    /// The data form's buffers as set (on the CPU or by the pre-pass on the device), read back
    /// whole: table, programs, ranges (for tests).
    pub fn tape_bytes(&self) -> Result<Option<[Vec<u8>; 3]>, Error> {
        let Some(buffers) = lock(&self.tape).clone() else {
            return Ok(None);
        };
        let [a, b, c] = buffers.map(|buffer| self.read(&buffer, buffer.size()));
        Ok(Some([a?, b?, c?]))
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
