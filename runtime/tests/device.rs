//! A render whose GPU device is lost midway (destroyed between two tiles, as a driver reset
//! would) ends with an error naming the loss: no panic, no hang, no image.

use crate::common::{compile, own_gpu};
use sdfc::gpu::BackendChoice;
use sdfc_compiler::emit;
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::view::View;

#[test]
fn losing_the_device_during_a_render_is_an_error() {
    // Its own device, not a shared one: it destroys it.
    let gpu = own_gpu(BackendChoice::Vulkan);
    let scene = compile("sphere(1)\nplane(y, -1)");
    let (module, _) = emit::module(&scene, Entry::Compute, &Options::from_scene(&scene)).unwrap();
    // Three tiles wide: the device goes after the first.
    let view = View::new(&scene.camera, 3 * sdfc::gpu::TILE, 64);
    let mut seen = 0;
    let result = gpu.render(&module, &view, None, |done, _| {
        seen = done;
        if done == 1 {
            gpu.lose_device();
        }
    });
    let error = result.expect_err("a render on a lost device must fail");
    // The device-loss callback's message, not the poll's.
    assert!(error.is_device_lost(), "{error:?}");
    assert!(
        error.to_string().contains("was lost (Destroyed)"),
        "{error}"
    );
    assert_eq!(seen, 1, "no tile after the loss");
    // And the next render on the same Gpu fails the same way, without a panic.
    let again = gpu.render(&module, &view, None, |_, _| {});
    assert!(again.is_err());
}
