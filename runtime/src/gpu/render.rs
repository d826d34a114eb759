//! Rendering a compiled compute module: prepared once, then run tile by tile for each
//! anti-aliasing sample and each animation frame, every frame read back and handed on.

use super::{Consumed, Error, Frame, Gpu, Layout, Source, TILE, lock};
use sdfc_compiler::passes::Pass;
use sdfc_compiler::view::View;

impl Gpu {
    /// Renders a compiled compute module (`emit` with `Entry::Compute`) for `view`, tile by
    /// tile; with `passes` (a module compiled with `Options::passes`), pass by pass, each
    /// handing its t and step counts to the next (Bálint §4). `progress` is told how many
    /// tiles are done.
    pub fn render(
        &self,
        module: &naga::Module,
        view: &View,
        passes: Option<&[Pass]>,
        progress: impl FnMut(u32, u32),
    ) -> Result<Frame, Error> {
        let mut out = None;
        self.render_samples(module, view, passes, &[view.jitter], progress, |f| {
            out = Some(f);
            Ok(())
        })?;
        Ok(out.expect("one frame"))
    }

    /// [`Gpu::render`] once per point of `jitters` (where in its pixel each frame's ray
    /// passes, `View::jitter`), the module prepared once; each frame is handed to `each` as
    /// it is read back, so that memory does not grow with the number of samples. `progress`
    /// counts the tiles of all frames.
    pub fn render_samples(
        &self,
        module: &naga::Module,
        view: &View,
        passes: Option<&[Pass]>,
        jitters: &[[f64; 2]],
        progress: impl FnMut(u32, u32),
        mut each: impl FnMut(Frame) -> Consumed,
    ) -> Result<(), Error> {
        let current = lock(&self.params).clone();
        self.render_sequence(
            module,
            (view, passes),
            jitters,
            &[current],
            progress,
            |_, f| each(f),
        )
    }

    /// [`Gpu::render_samples`] for each of `settings` (the `Params` uniform's bytes, one per
    /// picture: an animation's frames), the module prepared once; `each` gets the setting's
    /// index with every sample's frame.
    pub fn render_sequence(
        &self,
        module: &naga::Module,
        (view, passes): (&View, Option<&[Pass]>),
        jitters: &[[f64; 2]],
        settings: &[Vec<u8>],
        mut progress: impl FnMut(u32, u32),
        mut each: impl FnMut(usize, Frame) -> Consumed,
    ) -> Result<(), Error> {
        let layout = Layout::Full {
            passes: passes.is_some(),
        };
        let prepared = self.prepare(Source::Module(module), layout, view, passes, TILE)?;
        let per_frame = prepared.dispatches();
        let total = per_frame * (jitters.len() * settings.len()) as u32;
        let mut k = 0;
        for (s, bytes) in settings.iter().enumerate() {
            prepared.set_params(bytes);
            for &jitter in jitters {
                prepared.set_jitter(jitter);
                let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
                let before = k * per_frame;
                let seconds = prepared.run_tiles(|done, _| progress(before + done, total))?;
                if let Some(e) = pollster::block_on(validation.pop()) {
                    return Err(Error::InvalidModule(e.to_string()));
                }
                each(s, prepared.frame(seconds)?).map_err(Error::Consumer)?;
                k += 1;
            }
        }
        Ok(())
    }
}
