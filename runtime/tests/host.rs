//! The example host (`runtime/examples/host.rs`: its own render pipeline, camera and `Params`
//! filled from the manifest, `color` from the library) draws what `sdfc render` draws, at the
//! defaults and at other parameter values: the library, the manifest and docs/interface.md
//! are enough for a host.

use crate::common;

#[allow(dead_code)]
#[path = "../examples/host.rs"]
mod example;

use crate::common::{compile, gpu, render};
use sdfc_compiler::view::View;
use std::collections::HashMap;

#[test]
fn the_example_host_draws_what_render_draws() {
    let gpu = gpu();
    let path = common::root().join("examples/lamp.sdf");
    let source = std::fs::read_to_string(&path).unwrap();
    let scene = compile(&source);
    let (w, h) = (96, 64);
    let settings: [&[(&str, &[f64])]; 2] = [
        &[],
        &[("reach", &[1.0]), ("height", &[1.7]), ("time", &[2.0])],
    ];
    let mut pictures = Vec::new();
    for setting in settings {
        let values: HashMap<String, Vec<f64>> = setting
            .iter()
            .map(|(n, v)| (n.to_string(), v.to_vec()))
            .collect();
        let hosted = example::render(&example::Job {
            source: &source,
            size: (w, h),
            values: &values,
        })
        .unwrap();
        let here = scene.with_values(&values);
        let frame = render(&gpu, &here, &View::new(&here.camera, w, h));
        let (share, worst) = common::within_levels(&frame.color, &hosted, 2);
        println!(
            "{values:?}: the host within 2 levels of render on {:.2}% (worst {worst})",
            share * 100.0
        );
        assert!(share >= 0.998, "{values:?}: only {:.2}%", share * 100.0);
        pictures.push(hosted);
    }
    assert!(pictures[0] != pictures[1], "the values changed nothing");
}
