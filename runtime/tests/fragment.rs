//! The fragment entry in another engine's render pass, set up from its manifest alone: a
//! full-screen triangle of the host's own, an explicit bind group layout made of the
//! manifest's bindings and sizes, the `View` written at the manifest's offsets with the flags
//! where `fragment` puts them. Its WGSL goes through wgpu as any WGSL a user loads (naga's
//! front end, then Vulkan or GL), its SPIR-V straight to the Vulkan driver (lavapipe; wgpu's
//! passthrough, nothing parses it on the way); each picture equals `sdfc render`'s.

use crate::common::{compile, gpu, render, root, within_levels};
use sdfc_compiler::emit::{self, Output, Target};
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::manifest::{Origin, manifest};
use sdfc_compiler::view::{Fragment, View};
use serde_json::Value;
use std::borrow::Cow;
use std::collections::HashMap;

const HOST_VERTEX: &str =
    "@vertex fn host_vertex(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let xy = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(xy * 2.0 - 1.0, 0.0, 1.0);
}";

/// How the fragment shader reaches the device.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Source {
    /// WGSL text, parsed by naga's front end as a user's WGSL is.
    Wgsl,
    /// SPIR-V words handed to the Vulkan driver untouched.
    SpirvPassthrough,
}

/// A device on `backends` (with passthrough shaders where asked), or `None` if there is none.
fn device(backends: wgpu::Backends, passthrough: bool) -> Option<(wgpu::Device, wgpu::Queue)> {
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
    desc.backends = backends;
    let instance = wgpu::Instance::new(desc);
    let adapter = pollster::block_on(instance.request_adapter(&Default::default())).ok()?;
    let required_features = match passthrough {
        true => wgpu::Features::PASSTHROUGH_SHADERS,
        false => wgpu::Features::empty(),
    };
    if !adapter.features().contains(required_features) {
        return None;
    }
    let desc = wgpu::DeviceDescriptor {
        required_limits: adapter.limits(),
        required_features,
        ..Default::default()
    };
    pollster::block_on(adapter.request_device(&desc)).ok()
}

/// The uniform buffers' contents by binding, from the manifest: the `View` (camera, size and
/// the fragment flags at their offsets) and the `Params` (defaults, or `values`).
fn uniforms(m: &Value, view: &View, values: &HashMap<String, Vec<f64>>) -> HashMap<u32, Vec<u8>> {
    let mut out = HashMap::new();
    let struct_of = |name: &str| {
        m["structs"]
            .as_array()
            .unwrap()
            .iter()
            .find(|s| s["name"] == name)
            .unwrap()
            .clone()
    };
    let view_struct = struct_of(m["view"]["struct"].as_str().unwrap());
    let offset = |member: &str| {
        let all = view_struct["members"].as_array().unwrap();
        all.iter().find(|x| x["name"] == member).unwrap()["offset"]
            .as_u64()
            .unwrap() as usize
    };
    let mut bytes = vec![0u8; view_struct["size"].as_u64().unwrap() as usize];
    let mut put = |at: usize, x: f32| bytes[at..at + 4].copy_from_slice(&x.to_le_bytes());
    let rows = [
        ("eye", view.eye, 0.0),
        ("right", view.right, 0.5),
        ("up", view.up, 0.5),
        ("forward", view.forward, 0.0),
        (
            "size",
            glam::DVec3::new(f64::from(view.width), f64::from(view.height), view.pixel),
            0.0,
        ),
    ];
    for (name, v, w) in rows {
        for (i, x) in [v.x, v.y, v.z, w].into_iter().enumerate() {
            put(offset(name) + 4 * i, x as f32);
        }
    }
    for (flag, on) in [("y_up", view.fragment.y_up), ("srgb", view.fragment.srgb)] {
        let at = &m["fragment"][flag];
        let comp = at["component"].as_u64().unwrap() as usize;
        put(
            offset(at["field"].as_str().unwrap()) + 4 * comp,
            if on { 1.0 } else { 0.0 },
        );
    }
    for (i, x) in [0, 0, view.width, view.height].into_iter().enumerate() {
        bytes[offset("offset") + 4 * i..][..4].copy_from_slice(&x.to_le_bytes());
    }
    out.insert(
        m["view"]["binding"]["binding"].as_u64().unwrap() as u32,
        bytes,
    );
    if let Some(b) = m["params"]["binding"]["binding"].as_u64() {
        let mut bytes = vec![0u8; m["params"]["size"].as_u64().unwrap() as usize];
        for f in m["params"]["fields"].as_array().unwrap() {
            let default: Vec<f64> = f["default"]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            let value = values.get(f["name"].as_str().unwrap()).unwrap_or(&default);
            let at = f["offset"].as_u64().unwrap() as usize;
            for (i, x) in value.iter().enumerate() {
                bytes[at + 4 * i..][..4].copy_from_slice(&(*x as f32).to_le_bytes());
            }
        }
        out.insert(b as u32, bytes);
    }
    out
}

/// A shader module of SPIR-V `words` with the one entry point `entry`, given to the driver as is.
///
/// # Safety
/// The words must be valid SPIR-V for the device (`spirv-val` checks every version sdfc writes).
unsafe fn passthrough(device: &wgpu::Device, words: &[u32], entry: &str) -> wgpu::ShaderModule {
    unsafe {
        device.create_shader_module_passthrough(wgpu::ShaderModuleDescriptorPassthrough {
            label: Some(entry),
            entry_points: Cow::Owned(vec![wgpu::PassthroughShaderEntryPoint {
                name: Cow::Owned(entry.to_string()),
                workgroup_size: (0, 0, 0),
            }]),
            spirv: Some(Cow::Borrowed(words)),
            ..Default::default()
        })
    }
}

/// Draws the fragment entry (`code`: WGSL text or SPIR-V words) into a `format` target of
/// `view`'s size with the pipeline layout the manifest's bindings make; RGBA8 rows, y down.
fn draw(
    (device, queue): &(wgpu::Device, wgpu::Queue),
    (code, source): (&Output, Source),
    m: &Value,
    view: &View,
    values: &HashMap<String, Vec<f64>>,
    format: wgpu::TextureFormat,
) -> Vec<u8> {
    let vertex = naga::front::wgsl::parse_str(HOST_VERTEX).unwrap();
    let vertex = match source {
        Source::Wgsl => device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("host vertex"),
            source: wgpu::ShaderSource::Naga(Cow::Owned(vertex)),
        }),
        // (Both stages passed through: wgpu does not mix them.)
        Source::SpirvPassthrough => {
            let info = emit::validate(&vertex).unwrap();
            let pipeline = naga::back::spv::PipelineOptions {
                shader_stage: naga::ShaderStage::Vertex,
                entry_point: "host_vertex".into(),
            };
            let words =
                naga::back::spv::write_vec(&vertex, &info, &Default::default(), Some(&pipeline))
                    .unwrap();
            unsafe { passthrough(device, &words, "host_vertex") }
        }
    };
    let fragment = match (source, code) {
        (Source::Wgsl, Output::Text(wgsl)) => {
            let module = naga::front::wgsl::parse_str(wgsl).unwrap();
            device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("sdfc fragment"),
                source: wgpu::ShaderSource::Naga(Cow::Owned(module)),
            })
        }
        (Source::SpirvPassthrough, Output::Binary(words)) => unsafe {
            passthrough(device, words, "main")
        },
        _ => unreachable!("WGSL is text, SPIR-V words"),
    };
    let buffers = uniforms(m, view, values);
    let entries: Vec<wgpu::BindGroupLayoutEntry> = m["bindings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|b| b["space"] == "uniform")
        .map(|b| wgpu::BindGroupLayoutEntry {
            binding: b["binding"].as_u64().unwrap() as u32,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: std::num::NonZeroU64::new(b["size"].as_u64().unwrap()),
            },
            count: None,
        })
        .collect();
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: None,
        entries: &entries,
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: None,
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("host"),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: &vertex,
            entry_point: Some("host_vertex"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        fragment: Some(wgpu::FragmentState {
            module: &fragment,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            targets: &[Some(format.into())],
        }),
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        multiview_mask: None,
        cache: None,
    });
    let kept: Vec<(u32, wgpu::Buffer)> = entries
        .iter()
        .map(|e| {
            let bytes = &buffers[&e.binding];
            let b = device.create_buffer(&wgpu::BufferDescriptor {
                label: None,
                size: bytes.len() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            queue.write_buffer(&b, 0, bytes);
            (e.binding, b)
        })
        .collect();
    let group_entries: Vec<wgpu::BindGroupEntry> = kept
        .iter()
        .map(|(binding, b)| wgpu::BindGroupEntry {
            binding: *binding,
            resource: b.as_entire_binding(),
        })
        .collect();
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &layout,
        entries: &group_entries,
    });
    let (w, h) = (view.width, view.height);
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: None,
        size: wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let target = texture.create_view(&Default::default());
    let row = (4 * w).div_ceil(256) * 256;
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: u64::from(row * h),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &target,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            ..Default::default()
        });
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.draw(0..3, 0..1);
    }
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &readback,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row),
                rows_per_image: None,
            },
        },
        wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
    );
    queue.submit([encoder.finish()]);
    readback.slice(..).map_async(wgpu::MapMode::Read, |_| {});
    device.poll(wgpu::PollType::wait_indefinitely()).unwrap();
    let data = readback.slice(..).get_mapped_range().unwrap();
    (0..h)
        .flat_map(|y| data[(y * row) as usize..][..(4 * w) as usize].to_vec())
        .collect()
}

/// The lamp (parameters; at its defaults and other values), the composition (a union of more
/// than five parts) and the village through each of: WGSL on Vulkan, WGSL on GL, SPIR-V passed
/// to the Vulkan driver; into an `Rgba8UnormSrgb` target (the entry writes linear light) and
/// an `Rgba8Unorm` one (the `srgb` flag on). wgpu puts the origin top-left on every backend,
/// so `y_up` stays off. Each within 2 levels of `sdfc render` on 99.9% of pixels.
#[test]
fn the_fragment_entry_draws_in_a_wgpu_host_from_its_manifest() {
    let gpu = gpu();
    let (w, h) = (96u32, 64u32);
    let cases: [(&str, &str); 4] = [
        ("lamp", "{}"),
        (
            "lamp",
            r#"{"reach": [1.0], "height": [1.7], "time": [2.0]}"#,
        ),
        ("composition", "{}"),
        ("village", "{}"),
    ];
    let hosts = [
        ("WGSL on Vulkan", wgpu::Backends::VULKAN, Source::Wgsl),
        ("WGSL on GL", wgpu::Backends::GL, Source::Wgsl),
        (
            "SPIR-V to the Vulkan driver",
            wgpu::Backends::VULKAN,
            Source::SpirvPassthrough,
        ),
    ];
    let mut drawn = 0;
    for (label, backends, source) in hosts {
        let Some(dev) = device(backends, source == Source::SpirvPassthrough) else {
            assert!(std::env::var("CI").is_err(), "{label}: no device in CI");
            eprintln!("{label}: no such device here, skipped");
            continue;
        };
        for (name, json) in cases {
            let text =
                std::fs::read_to_string(root().join(format!("examples/{name}.sdf"))).unwrap();
            let scene = compile(&text);
            let mut options = Options::from_scene(&scene);
            if source == Source::SpirvPassthrough {
                // wgpu's Vulkan back end numbers a layout's bindings 0, 1, 2… in order and
                // rewrites the shaders it translates to match, but not passed-through SPIR-V:
                // give `Params` the binding it will have (`--params-binding 1`).
                options.params_binding = 1;
            }
            let (module, info) = emit::module(&scene, Entry::Fragment, &options).unwrap();
            let target = match source {
                Source::Wgsl => Target::Wgsl,
                Source::SpirvPassthrough => Target::Spirv,
            };
            let (code, reflection) =
                emit::write_reflected(&module, &info, target, Entry::Fragment, &Default::default())
                    .unwrap();
            let origin = Origin {
                volume_files: &[],
                data: None,
                scene: name,
                target: "wgsl",
                entry: Entry::Fragment,
                prefix: None,
                written: Some((&code, &reflection)),
            };
            let m = manifest(&scene, &module, &origin);
            let values: HashMap<String, Vec<f64>> = serde_json::from_str(json).unwrap();
            let here = scene.with_values(&values);
            let frame = render(&gpu, &here, &View::new(&here.camera, w, h));
            for (format, srgb) in [
                (wgpu::TextureFormat::Rgba8UnormSrgb, false),
                (wgpu::TextureFormat::Rgba8Unorm, true),
            ] {
                let mut view = View::new(&scene.camera, w, h);
                view.fragment = Fragment { y_up: false, srgb };
                let px = draw(&dev, (&code, source), &m, &view, &values, format);
                let (share, worst) = within_levels(&frame.color, &px, 2);
                println!(
                    "{label}, {name} {json}, {format:?}: within 2 levels on {:.2}% (worst {worst})",
                    share * 100.0
                );
                assert!(
                    share >= 0.999,
                    "{label}, {name} {json}, {format:?}: {:.2}%",
                    share * 100.0
                );
                drawn += 1;
            }
        }
    }
    crate::common::report(&format!(
        "wgpu hosts from the manifest (WGSL on Vulkan and GL, SPIR-V passed to lavapipe): {drawn} pictures, each >= 99.9% within 2 levels of sdfc render"
    ));
    assert!(drawn >= 8, "only {drawn} pictures");
}
