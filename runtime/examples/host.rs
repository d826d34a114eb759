//! A host for sdfc's library output, as another engine would write one: its own full-screen
//! render pass (vertex + fragment, no compute), its own camera uniform, the scene's `Params`
//! filled from the manifest, and `color(ro, rd, pixel)` from the library; rendered headless
//! into an sRGB texture and saved as a PNG.
//!
//! ```sh
//! cargo run --release --example host -- examples/lamp.sdf host.png reach=60deg time=1.5
//! ```
//!
//! It uses only what docs/interface.md promises: the library's WGSL, the manifest's `params`
//! (offsets, defaults) and camera, and the `Params` binding (group 0, binding 9).

use std::collections::HashMap;

/// The host's own shader code, appended to the library: a full-screen triangle and a fragment
/// stage that turns the pixel into a camera ray (the same pinhole camera as `sdfc render`:
/// docs/interface.md) and asks the library for its colour.
const HOST_WGSL: &str = r#"
struct HostCamera {
    eye: vec4<f32>,
    right: vec4<f32>,
    up: vec4<f32>,
    forward: vec4<f32>,
    size: vec4<f32>,
}
@group(1) @binding(0) var<uniform> camera: HostCamera;

@vertex
fn host_vertex(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let xy = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(xy * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn host_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let u = 2.0 * position.x / camera.size.x - 1.0;
    let v = 1.0 - 2.0 * position.y / camera.size.y;
    let rd = normalize(camera.forward.xyz + camera.right.xyz * u + camera.up.xyz * v);
    let c = color(camera.eye.xyz, rd, camera.size.z);
    return vec4<f32>(c.rgb, 1.0);
}
"#;

/// What the host renders: a scene file, the image size and parameter values by name (numbers
/// in the manifest's units: radians for angles).
pub struct Job<'a> {
    /// The scene's source text.
    pub source: &'a str,
    /// Width and height in pixels.
    pub size: (u32, u32),
    /// Parameter values by name (components), others at their defaults.
    pub values: &'a HashMap<String, Vec<f64>>,
}

/// Compiles the scene's library and manifest as `sdfc emit --entry library --manifest` would,
/// renders it with the host's pipeline and returns the sRGB RGBA8 pixels (row-major, y down).
pub fn render(job: &Job) -> Result<Vec<u8>, String> {
    use sdfc_compiler::emit::{self, Output, Target};
    use sdfc_compiler::lower::{Entry, tracer::Options};
    let checked = sdfc_compiler::check::compile(job.source);
    let scene = checked
        .scene
        .ok_or("the scene has errors (run `sdfc check`)")?;
    let (module, info) =
        emit::module(&scene, Entry::Library, &Options::from_scene(&scene)).map_err(|e| e.0)?;
    let Output::Text(library) =
        emit::write(&module, &info, Target::Wgsl, Entry::Library).map_err(|e| e.0)?
    else {
        unreachable!("WGSL is text")
    };
    let origin = sdfc_compiler::manifest::Origin {
        volume_files: &[],
        data: None,
        scene: "host",
        target: "wgsl",
        entry: Entry::Library,
        prefix: None,
        written: None,
    };
    let manifest = sdfc_compiler::manifest::manifest(&scene, &module, &origin);
    let params = params_bytes(&manifest, job.values)?;
    let camera = camera_bytes(&manifest, job.size);
    draw(
        &format!("{library}\n{HOST_WGSL}"),
        params,
        &camera,
        job.size,
    )
}

/// The `Params` uniform from the manifest: each field's default, or the value asked for, at
/// its offset; and its binding in group 0, if the shader reads it.
fn params_bytes(
    manifest: &serde_json::Value,
    values: &HashMap<String, Vec<f64>>,
) -> Result<(Vec<u8>, Option<u32>), String> {
    let size = manifest["params"]["size"].as_u64().unwrap_or(0) as usize;
    let mut bytes = vec![0u8; size];
    for f in manifest["params"]["fields"]
        .as_array()
        .into_iter()
        .flatten()
    {
        let name = f["name"].as_str().unwrap_or("");
        let default: Vec<f64> = f["default"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(|x| x.as_f64())
            .collect();
        let value = values.get(name).unwrap_or(&default);
        if value.len() != default.len() {
            return Err(format!("`{name}` takes {} numbers", default.len()));
        }
        let offset = f["offset"].as_u64().unwrap_or(0) as usize;
        for (i, x) in value.iter().enumerate() {
            let at = offset + 4 * i;
            bytes[at..at + 4].copy_from_slice(&(*x as f32).to_le_bytes());
        }
    }
    let binding = manifest["params"]["binding"]["binding"]
        .as_u64()
        .map(|b| b as u32);
    Ok((bytes, binding))
}

/// The host's camera uniform from the manifest's camera: eye, right and up scaled by the
/// half field of view (and the aspect), forward, and (width, height, pixel footprint).
fn camera_bytes(manifest: &serde_json::Value, (w, h): (u32, u32)) -> Vec<u8> {
    let v = |key: &str| {
        let a: Vec<f64> = manifest["camera"][key]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(|x| x.as_f64())
            .collect();
        glam::DVec3::new(a[0], a[1], a[2])
    };
    let (eye, target, up) = (v("eye"), v("target"), v("up"));
    let fov = manifest["camera"]["fov_degrees"]
        .as_f64()
        .unwrap_or(45.0)
        .to_radians();
    let forward = (target - eye).normalize();
    let right = forward.cross(up).normalize();
    let up = right.cross(forward);
    let t = (fov / 2.0).tan();
    let aspect = f64::from(w) / f64::from(h);
    let rows = [
        eye.extend(0.0),
        (right * t * aspect).extend(0.0),
        (up * t).extend(0.0),
        forward.extend(0.0),
        glam::DVec4::new(f64::from(w), f64::from(h), t / f64::from(h), 0.0),
    ];
    rows.iter()
        .flat_map(|r| r.to_array())
        .flat_map(|x| (x as f32).to_le_bytes())
        .collect()
}

/// Renders the full-screen pass into an `Rgba8UnormSrgb` texture and reads it back.
fn draw(
    wgsl: &str,
    params: (Vec<u8>, Option<u32>),
    camera: &[u8],
    (w, h): (u32, u32),
) -> Result<Vec<u8>, String> {
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
    desc.backends = wgpu::Backends::VULKAN | wgpu::Backends::GL;
    let instance = wgpu::Instance::new(desc);
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
        compatible_surface: None,
        ..Default::default()
    }))
    .map_err(|e| format!("no GPU adapter: {e}"))?;
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        required_limits: adapter.limits(),
        ..Default::default()
    }))
    .map_err(|e| e.to_string())?;
    // (This build of wgpu takes naga modules; `ShaderSource::Wgsl` with its `wgsl` feature.)
    let module = naga::front::wgsl::parse_str(wgsl).map_err(|e| e.emit_to_string(wgsl))?;
    let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("host"),
        source: wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(module)),
    });
    let format = wgpu::TextureFormat::Rgba8UnormSrgb;
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("host"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &shader,
            entry_point: Some("host_vertex"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        fragment: Some(wgpu::FragmentState {
            module: &shader,
            entry_point: Some("host_fragment"),
            compilation_options: Default::default(),
            targets: &[Some(format.into())],
        }),
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        multiview_mask: None,
        cache: None,
    });
    let uniform = |label: &str, bytes: &[u8]| {
        let b = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: bytes.len().max(16) as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        queue.write_buffer(&b, 0, bytes);
        b
    };
    let camera_buffer = uniform("camera", camera);
    let camera_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("camera"),
        layout: &pipeline.get_bind_group_layout(1),
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: camera_buffer.as_entire_binding(),
        }],
    });
    // The scene's parameters, where the manifest gives their binding (docs/interface.md).
    let params_buffer = params
        .1
        .map(|binding| (uniform("params", &params.0), binding));
    let params_group = params_buffer.as_ref().map(|(b, binding)| {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("params"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry {
                binding: *binding,
                resource: b.as_entire_binding(),
            }],
        })
    });
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("frame"),
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
    let view = texture.create_view(&Default::default());
    let row = (4 * w).div_ceil(256) * 256;
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: u64::from(row * h),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("host"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &view,
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
        if let Some(g) = &params_group {
            pass.set_bind_group(0, g, &[]);
        }
        pass.set_bind_group(1, &camera_group, &[]);
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
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| e.to_string())?;
    let data = readback
        .slice(..)
        .get_mapped_range()
        .map_err(|e| e.to_string())?;
    let mut pixels = Vec::with_capacity((4 * w * h) as usize);
    for y in 0..h {
        let start = (y * row) as usize;
        pixels.extend_from_slice(&data[start..start + (4 * w) as usize]);
    }
    Ok(pixels)
}

#[allow(dead_code)]
fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let scene = args.first().map_or("examples/lamp.sdf", String::as_str);
    let out = args.get(1).map_or("host.png", String::as_str);
    let mut values = HashMap::new();
    for a in args.iter().skip(2) {
        let Some((name, value)) = a.split_once('=') else {
            eprintln!("error: `{a}` is not NAME=VALUE");
            std::process::exit(1);
        };
        let (text, factor) = match value.strip_suffix("deg") {
            Some(t) => (t, std::f64::consts::PI / 180.0),
            None => (value, 1.0),
        };
        let parsed: Result<Vec<f64>, _> =
            text.split(',').map(|x| x.trim().parse::<f64>()).collect();
        match parsed {
            Ok(v) => values.insert(name.to_string(), v.iter().map(|x| x * factor).collect()),
            Err(_) => {
                eprintln!("error: `{value}` is not a number or x,y,z");
                std::process::exit(1);
            }
        };
    }
    let source = std::fs::read_to_string(scene).unwrap_or_else(|e| {
        eprintln!("error: cannot read `{scene}`: {e}");
        std::process::exit(1);
    });
    let size = (640, 400);
    let job = Job {
        source: &source,
        size,
        values: &values,
    };
    match render(&job).and_then(|px| {
        image::RgbaImage::from_raw(size.0, size.1, px)
            .ok_or("a whole image".to_string())?
            .save(out)
            .map_err(|e| e.to_string())
    }) {
        Ok(()) => eprintln!("wrote {out}"),
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}
