//! The data form's pre-pass on the GPU (issue 33 §2, `lower/data/prune.rs`) against the CPU's
//! (`tape::data::data`, the reference): cell by cell, its programs are the CPU's — or, where
//! f32's wider margin keeps a part more, give the whole tree's value bit for bit at points of
//! the cell — and the pictures drawn from them are the same, pixel for pixel.

use crate::common::{compile, gpu, report};
use crate::data_form::balls;
use glam::DVec3;
use sdfc_compiler::emit;
use sdfc_compiler::lower::Entry;
use sdfc_compiler::lower::tracer::{Form, Options};
use sdfc_compiler::tape::program::{self, Code, Table};
use sdfc_compiler::tape::{cells, data};
use sdfc_compiler::view::View;

/// The scenes: blended balls on a plane (a proxy, nesting), balls of materials blended in
/// nested groups (a stack), a hard union, and cuts (largest folds, negated children).
fn scenes() -> Vec<(&'static str, String)> {
    let camera = "camera { eye (0, 1, -4)  target (0, 0, 0) }";
    let mats = "material red { color #d04038 }\nmaterial blue { color #3050d0 }\nmaterial gold { color #d0a038 }";
    vec![
        (
            "300 blended balls on a plane",
            format!(
                "{camera}\nsmooth_union(0.03) {{\n{}\n}}\nplane(y, -1.2)",
                balls(300, false)
            ),
        ),
        (
            "nested blends of materials",
            format!(
                "{mats}\n{camera}\nsmooth_union(0.2) {{\nsmooth_union(0.15) {{\n{}\n}}\nsmooth_union(0.15) {{\n{}\n}} : gold\nplane(y, -1.1) : blue\n}}",
                balls(60, true),
                balls(90, true)
            ),
        ),
        (
            "200 balls, hard",
            format!("{mats}\n{camera}\nunion {{\n{}\n}}", balls(200, true)),
        ),
        (
            "cuts",
            format!(
                "{mats}\ncamera {{ eye (2, 2, -4)  target (0, 0, 0) }}\nsubtract {{\n  box((1.6, 1.2, 1.4)) : red\n  smooth_union(0.05) {{\n{}\n}}\n  smooth_intersect(0.1) {{ sphere(0.7) at (-0.6, 0, 0)  box((0.8, 0.8, 3)) |> rotate(y, 30deg) }}\n}}\nplane(y, -0.6)",
                balls(120, false)
            ),
        ),
    ]
}

/// Little-endian u32 words.
fn words(bytes: &[u8]) -> Vec<u32> {
    bytes
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

#[test]
fn the_gpu_prepass_prunes_as_the_cpu_does() {
    let gpu = gpu();
    let mut said = Vec::new();
    for (name, source) in scenes() {
        let scene = compile(&source);
        let (tree, layout) = data::layout(&scene, None).expect("a data form");
        let seed = sdfc_compiler::tape::seed::seed(&scene, &tree, &layout)
            .expect("a seed")
            .expect("a grid");
        let pruner = gpu.pruner(&scene).unwrap().expect("a pre-pass");
        gpu.set_scene(&scene);
        let made = gpu.prune(&pruner, &seed).unwrap().expect("room");
        let [_, code, ranges] = gpu.tape_bytes().unwrap().expect("buffers");
        let (code, ranges) = (words(&code), words(&ranges));
        // The CPU's programs, cell by cell, in the same order.
        let table = Table::new(&scene, &tree).unwrap();
        let grid = (layout.lo, layout.size, layout.n);
        let cpu = cells::map_grid(&scene, &tree, grid, |p, _, _| {
            program::encode(&table, &p).unwrap().words
        });
        let whole = program::encode(&table, &tree).unwrap();
        assert_eq!(made.cells, cpu.len(), "{name}: cells");
        let (mut same, mut checked) = (0, 0);
        let mut x: u64 = 0x2545_f491;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x % 1_000_000) as f64 / 1_000_000.0
        };
        let [nx, ny, _] = layout.n;
        let cpu_data = data::data(&scene, &tree, &layout).unwrap();
        let (mut far_gpu, mut far_cpu) = (0, 0);
        for (i, want) in cpu.iter().enumerate() {
            let at = 2 * (data::HEADER + i);
            let (len, clearance) = data::unpack_count(ranges[at + 1], layout.size);
            let start = ranges[at] as usize;
            let got = &code[start..start + len as usize];
            let cpu_count = cpu_data.ranges[data::HEADER + i][1];
            let cpu_clearance = data::unpack_count(cpu_count, layout.size).1;
            far_gpu += usize::from(clearance.is_some());
            far_cpu += usize::from(cpu_clearance.is_some());
            let c = DVec3::new(
                (i % nx) as f64,
                ((i / nx) % ny) as f64,
                (i / (nx * ny)) as f64,
            );
            let mut at_random =
                || layout.lo + (c + DVec3::new(next(), next(), next())) * layout.size;
            // A far cell's clearance (the device's, the CPU's) is below the field in it.
            if clearance.is_some() || cpu_clearance.is_some() {
                for _ in 0..4 {
                    let p = at_random();
                    let field = program::run(&table, &whole, p).0;
                    for clear in [clearance, cpu_clearance].into_iter().flatten() {
                        assert!(
                            clear <= field,
                            "{name}: cell {i} at {p}: clearance {clear} above the field {field}"
                        );
                    }
                }
            }
            if got == want.as_slice() {
                same += 1;
                continue;
            }
            // Kept more than the CPU: still the whole field inside the cell.
            let ours = Code {
                words: got.to_vec(),
                leaves: 0,
                depth: 0,
            };
            for _ in 0..20 {
                let p = at_random();
                let (a, b) = (
                    program::run(&table, &ours, p),
                    program::run(&table, &whole, p),
                );
                assert!(
                    a.0.to_bits() == b.0.to_bits() && a.1 == b.1,
                    "{name}: cell {i} at {p}: {a:?} against the whole program's {b:?}\nGPU {got:?}\nCPU {want:?}"
                );
                checked += 1;
            }
        }
        // The pictures drawn from either: with the far cells' marks left out (the programs
        // alone), the same pixel for pixel; with them, the camera's rays step by clearances
        // that differ by f32's margin (a few 64ths of a cell), so a hit lands elsewhere within
        // ε: hit masks, materials and colours agree but on silhouettes' few pixels.
        let view = View::new(&scene.camera, 160, 90);
        let options = Options {
            form: Form::Data,
            ..Options::from_scene(&scene)
        };
        let (module, _) = emit::module(&scene, Entry::Compute, &options).unwrap();
        let on_gpu = gpu.render(&module, &view, None, |_, _| {}).unwrap();
        let [nodes, _, _] = gpu.tape_bytes().unwrap().expect("buffers");
        let unmarked = |ranges: &[[u32; 2]]| -> Vec<[u32; 2]> {
            ranges
                .iter()
                .enumerate()
                .map(
                    |(i, &[s, c])| match i >= data::HEADER && i < data::HEADER + cpu.len() {
                        true => [s, data::unpack_count(c, layout.size).0],
                        false => [s, c],
                    },
                )
                .collect()
        };
        let gpu_ranges: Vec<[u32; 2]> = ranges.chunks_exact(2).map(|r| [r[0], r[1]]).collect();
        let gpu_plain = data::Data {
            nodes: words(&nodes)
                .chunks_exact(4)
                .map(|w| [w[0], w[1], w[2], w[3]])
                .collect(),
            code: code.clone(),
            ranges: unmarked(&gpu_ranges[..data::HEADER + cpu.len() + 1]),
            mean_leaves: made.mean_leaves,
        };
        let cpu_plain = data::Data {
            ranges: unmarked(&cpu_data.ranges),
            ..cpu_data.clone()
        };
        let draw = |d: &data::Data| {
            gpu.set_tape(Some(d)).unwrap();
            gpu.render(&module, &view, None, |_, _| {}).unwrap()
        };
        let on_cpu = draw(&cpu_data);
        let (plain_gpu, plain_cpu) = (draw(&gpu_plain), draw(&cpu_plain));
        gpu.set_tape(None).unwrap();
        let pixels = on_cpu.color.len();
        let exact = (0..pixels)
            .filter(|&i| {
                plain_cpu.color[i] != plain_gpu.color[i]
                    || plain_cpu.depth[i].to_bits() != plain_gpu.depth[i].to_bits()
                    || plain_cpu.material[i] != plain_gpu.material[i]
            })
            .count();
        assert_eq!(exact, 0, "{name}: pixels apart without the far marks");
        let masks = (0..pixels)
            .filter(|&i| (on_cpu.depth[i] < 0.0) != (on_gpu.depth[i] < 0.0))
            .count();
        let materials = (0..pixels)
            .filter(|&i| on_cpu.material[i] != on_gpu.material[i])
            .count();
        let colours = (0..pixels)
            .filter(|&i| {
                let (a, b) = (on_cpu.color[i].to_le_bytes(), on_gpu.color[i].to_le_bytes());
                (0..3).any(|k| a[k].abs_diff(b[k]) > 2)
            })
            .count();
        assert!(
            masks <= pixels / 500 && materials <= pixels / 500 && colours <= pixels / 40,
            "{name}: of {pixels} pixels {masks} hit masks, {materials} materials, {colours} colours differ"
        );
        let apart = format!("{masks}/{materials}/{colours}");
        assert!(
            (made.mean_leaves - cpu_data.mean_leaves).abs() <= 0.05 * cpu_data.mean_leaves,
            "{name}: {} leaves a cell on the GPU, {} on the CPU",
            made.mean_leaves,
            cpu_data.mean_leaves
        );
        said.push(format!(
            "{name}: {same} of {} cells' programs equal, {checked} points checked in the rest, {far_gpu} far cells (CPU {far_cpu}), 0 pixels apart without them, {apart} of {pixels} hit masks/materials/colours with them",
            cpu.len()
        ));
    }
    report(&format!(
        "GPU pre-pass against the CPU's: {}",
        said.join("; ")
    ));
}

/// On the command line: `render --prepass gpu` and `--prepass cpu` write the same picture, byte
/// for byte (`auto` takes the CPU below 1000 parts: the same again); `--prepass` on a scene
/// drawn inline is an error that says so.
#[test]
fn the_command_line_prunes_where_asked_with_the_same_picture() {
    use crate::common::{refused, scratch, succeeded, write};
    let dir = scratch("prepass-cli");
    let source = format!(
        "camera {{ eye (0, 1, -4)  target (0, 0, 0) }}\nsmooth_union(0.03) {{\n{}\n}}\nplane(y, -1.2)",
        balls(150, false)
    );
    let file = write(&dir, "balls.sdf", &source);
    let picture = |how: &str| {
        let out = dir.join(format!("{how}.png"));
        let out = out.to_str().unwrap();
        succeeded(&[
            "render",
            &file,
            "-o",
            out,
            "--size",
            "96x64",
            "--prepass",
            how,
        ]);
        std::fs::read(out).unwrap()
    };
    let (gpu, cpu, auto) = (picture("gpu"), picture("cpu"), picture("auto"));
    assert!(gpu == cpu && cpu == auto, "the pictures differ");
    let out = dir.join("inline.png");
    refused(
        &[
            "render",
            &file,
            "-o",
            out.to_str().unwrap(),
            "--form",
            "inline",
            "--prepass",
            "gpu",
        ],
        "`--prepass gpu` is for the data form",
        &out,
    );
}
