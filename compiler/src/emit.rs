//! Emitting: compact and validate the lowered module, then write it with one of naga's back ends.

use crate::lower::{self, Entry, tracer::Options};
use crate::scene::Scene;
use naga::back;
use naga::valid::{Capabilities, ModuleInfo, ValidationFlags, Validator};

/// Output languages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// WGSL text.
    Wgsl,
    /// SPIR-V binary (1.3).
    Spirv,
    /// GLSL 4.50 (Vulkan-style bindings, for `glslangValidator -V`).
    Glsl,
    /// Metal Shading Language.
    Msl,
    /// HLSL (shader model 5.1).
    Hlsl,
}

impl Target {
    /// Its name as `--target` and the manifest spell it.
    pub fn name(self) -> &'static str {
        match self {
            Target::Wgsl => "wgsl",
            Target::Spirv => "spirv",
            Target::Glsl => "glsl",
            Target::Msl => "msl",
            Target::Hlsl => "hlsl",
        }
    }
}

/// What an emit produces: text, or SPIR-V words.
#[derive(Clone, Debug, PartialEq)]
pub enum Output {
    /// Source text.
    Text(String),
    /// SPIR-V binary.
    Binary(Vec<u32>),
}

/// A compiler bug: the lowered module failed validation or a back end refused it.
#[derive(Debug)]
pub struct InternalError(pub String);

/// Lowers, compacts and validates a scene for an entry kind.
pub fn module(
    scene: &Scene,
    entry: Entry,
    options: &Options,
) -> Result<(naga::Module, ModuleInfo), InternalError> {
    let mut module = lower::lower(scene, entry, options);
    let keep = if entry == Entry::Library {
        naga::compact::KeepUnused::Yes
    } else {
        naga::compact::KeepUnused::No
    };
    naga::compact::compact(&mut module, keep);
    let info = validate(&module)?;
    Ok((module, info))
}

/// The data form's pre-pass module for `scene` (`lower::prune`), compacted and validated, with
/// the fold nesting its arrays hold; none where the scene has no data form.
pub fn prune_module(
    scene: &Scene,
) -> Result<Option<(naga::Module, ModuleInfo, usize)>, InternalError> {
    let Some((mut module, height)) = lower::prune(scene) else {
        return Ok(None);
    };
    naga::compact::compact(&mut module, naga::compact::KeepUnused::No);
    let info = validate(&module)?;
    Ok(Some((module, info, height)))
}

/// Runs naga's validator with every check on.
pub fn validate(module: &naga::Module) -> Result<ModuleInfo, InternalError> {
    Validator::new(ValidationFlags::all(), Capabilities::empty())
        .validate(module)
        .map_err(|e| {
            InternalError(format!(
                "the generated module is invalid: {}",
                e.emit_to_string("")
            ))
        })
}

/// The library's placeholder `main`: it loads every global (the parameters),
/// because naga's GLSL back end writes only the globals an entry point uses, and leaves out
/// every function that reads another — the whole library of a scene with parameters.
fn touching_globals(module: &mut naga::Module) -> naga::Function {
    let mut f = naga::Function::default();
    let ivec3 = module.types.insert(
        naga::Type {
            name: None,
            inner: naga::TypeInner::Vector {
                size: naga::VectorSize::Tri,
                scalar: naga::Scalar::I32,
            },
        },
        naga::Span::UNDEFINED,
    );
    for (h, g) in module.global_variables.iter() {
        let runtime_sized = matches!(
            module.types[g.ty].inner,
            naga::TypeInner::Array {
                size: naga::ArraySize::Dynamic,
                ..
            }
        );
        if runtime_sized {
            continue;
        }
        let ptr = f
            .expressions
            .append(naga::Expression::GlobalVariable(h), naga::Span::UNDEFINED);
        let level = f.expressions.append(
            naga::Expression::Literal(naga::Literal::I32(0)),
            naga::Span::UNDEFINED,
        );
        let origin = f
            .expressions
            .append(naga::Expression::ZeroValue(ivec3), naga::Span::UNDEFINED);
        let start = f.expressions.len();
        // A texture (a baked volume) is a handle, not a pointer: a texel is loaded instead
        // (the GLSL writer keeps only functions whose uses of globals `main`'s cover).
        let touch = match g.space {
            naga::AddressSpace::Handle => naga::Expression::ImageLoad {
                image: ptr,
                coordinate: origin,
                array_index: None,
                sample: None,
                level: Some(level),
            },
            _ => naga::Expression::Load { pointer: ptr },
        };
        f.expressions.append(touch, naga::Span::UNDEFINED);
        let range = f.expressions.range_from(start);
        f.body
            .push(naga::Statement::Emit(range), naga::Span::UNDEFINED);
    }
    f
}

/// Binding map for GLSL with Vulkan semantics and HLSL: group 0, binding n → binding n.
fn glsl_bindings(module: &naga::Module) -> back::glsl::BindingMap {
    module
        .global_variables
        .iter()
        .filter_map(|(_, g)| g.binding)
        .map(|rb| (rb, rb.binding as u8))
        .collect()
}

/// The Metal argument-buffer slot of the buffer that holds the sizes of runtime-sized
/// storage arrays (naga's `_mslBufferSizes`), after every binding's own slot.
pub const MSL_SIZES_SLOT: u8 = 30;

/// The MSL resource map of the entry point `main`: binding n of group 0 is `[[buffer(n)]]`
/// (writable for storage buffers), or `[[texture(n)]]` for a texture, the array sizes at [`MSL_SIZES_SLOT`]; no fake bindings.
fn msl_bindings(module: &naga::Module) -> back::msl::EntryPointResourceMap {
    let resources = module
        .global_variables
        .iter()
        .filter_map(|(_, g)| g.binding.map(|rb| (rb, g.space)))
        .map(|(rb, space)| {
            let mutable = matches!(
                space,
                naga::AddressSpace::Storage { access } if access.contains(naga::StorageAccess::STORE)
            );
            // A texture (a baked volume) takes the texture slot of its binding's number.
            let target = match space {
                naga::AddressSpace::Handle => back::msl::BindTarget {
                    texture: Some(rb.binding as u8),
                    ..Default::default()
                },
                _ => back::msl::BindTarget {
                    buffer: Some(rb.binding as u8),
                    mutable,
                    ..Default::default()
                },
            };
            (rb, target)
        })
        .collect();
    let mut map = back::msl::EntryPointResourceMap::new();
    map.insert(
        "main".to_string(),
        back::msl::EntryPointResources {
            resources,
            sizes_buffer: Some(MSL_SIZES_SLOT),
            ..Default::default()
        },
    );
    map
}

/// Writes a validated module in the target language.
pub fn write(
    module: &naga::Module,
    info: &ModuleInfo,
    target: Target,
    entry: Entry,
) -> Result<Output, InternalError> {
    write_with(module, info, target, entry, &Settings::default())
}

/// Back-end settings a user may choose.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Settings {
    /// SPIR-V version (major, minor): 1.0 to 1.6; 1.3 by default (Vulkan 1.1).
    pub spirv_version: (u8, u8),
    /// The GLSL dialect.
    pub glsl_version: GlslVersion,
}

impl Default for Settings {
    fn default() -> Settings {
        Settings {
            spirv_version: (1, 3),
            glsl_version: GlslVersion::Core450,
        }
    }
}

/// The GLSL dialect written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GlslVersion {
    /// Desktop GLSL 4.50 core, Vulkan-style bindings.
    Core450,
    /// GLSL ES 3.10 (OpenGL ES 3.1: compute shaders and storage buffers).
    Es310,
    /// GLSL ES 3.00 (WebGL 2, OpenGL ES 3.0): fragment shaders only; no compute.
    Es300,
}

impl GlslVersion {
    /// Whether the dialect has compute shaders.
    pub fn has_compute(self) -> bool {
        self != GlslVersion::Es300
    }

    fn naga(self) -> back::glsl::Version {
        match self {
            GlslVersion::Core450 => back::glsl::Version::Desktop(450),
            GlslVersion::Es310 => back::glsl::Version::Embedded {
                version: 310,
                is_webgl: false,
            },
            GlslVersion::Es300 => back::glsl::Version::Embedded {
                version: 300,
                is_webgl: true,
            },
        }
    }
}

/// [`write`] with chosen back-end settings.
pub fn write_with(
    module: &naga::Module,
    info: &ModuleInfo,
    target: Target,
    entry: Entry,
    settings: &Settings,
) -> Result<Output, InternalError> {
    write_reflected(module, info, target, entry, settings).map(|(out, _)| out)
}

/// What a back end wrote besides the code: the names a host binds by that only the back end
/// knows.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Reflection {
    /// GLSL: each uniform or storage block's name as written (`View_block_0Fragment`), and
    /// each texture's sampler uniform's, by binding — numbered in the order the writer met them, so a WebGL2 host, which binds
    /// blocks by name, must read them here. Empty for the other targets.
    pub blocks: Vec<(u32, String)>,
}

/// [`write_with`], and what the back end named ([`Reflection`]).
pub fn write_reflected(
    module: &naga::Module,
    info: &ModuleInfo,
    target: Target,
    entry: Entry,
    settings: &Settings,
) -> Result<(Output, Reflection), InternalError> {
    let err =
        |e: &dyn std::fmt::Display| InternalError(format!("the {target:?} back end failed: {e}"));
    let stage = match entry {
        Entry::Compute | Entry::Rays | Entry::Field | Entry::Trace => naga::ShaderStage::Compute,
        _ => naga::ShaderStage::Fragment,
    };
    // Only GLSL's writer names something a host must bind by (its blocks).
    let out = match target {
        Target::Glsl => return write_glsl_reflected(module, info, entry, settings),
        // SPIR-V for Vulkan needs an entry point: add an empty compute `main`; the library
        // functions are written beside it.
        Target::Spirv if entry == Entry::Library => {
            let (m, info) = with_main(module, target, settings)?;
            return write_reflected(&m, &info, target, Entry::Compute, settings);
        }
        Target::Wgsl => back::wgsl::write_string(module, info, back::wgsl::WriterFlags::empty())
            .map(Output::Text)
            .map_err(|e| err(&e)),
        Target::Spirv => {
            let options = back::spv::Options {
                lang_version: settings.spirv_version,
                ..Default::default()
            };
            let pipeline = (entry != Entry::Library).then(|| back::spv::PipelineOptions {
                shader_stage: stage,
                entry_point: "main".into(),
            });
            back::spv::write_vec(module, info, &options, pipeline.as_ref())
                .map(Output::Binary)
                .map_err(|e| err(&e))
        }
        Target::Msl => {
            let options = back::msl::Options {
                per_entry_point_map: msl_bindings(module),
                fake_missing_bindings: false,
                ..Default::default()
            };
            let pipeline = back::msl::PipelineOptions::default();
            back::msl::write_string(module, info, &options, &pipeline)
                .map(|(s, _)| Output::Text(s))
                .map_err(|e| err(&e))
        }
        Target::Hlsl => {
            let options = back::hlsl::Options::default();
            let mut s = String::new();
            back::hlsl::Writer::new(&mut s, &options, &back::hlsl::PipelineOptions::default())
                .write(module, info, None)
                .map_err(|e| err(&e))?;
            Ok(Output::Text(s))
        }
    };
    out.map(|o| (o, Reflection::default()))
}

/// GLSL and the names of its blocks; a library is written with an empty `main`, as SPIR-V's.
fn write_glsl_reflected(
    module: &naga::Module,
    info: &ModuleInfo,
    entry: Entry,
    settings: &Settings,
) -> Result<(Output, Reflection), InternalError> {
    let err = |e: &dyn std::fmt::Display| InternalError(format!("the Glsl back end failed: {e}"));
    if entry == Entry::Library {
        let (m, info) = with_main(module, Target::Glsl, settings)?;
        let stage = match settings.glsl_version.has_compute() {
            true => Entry::Compute,
            false => Entry::Fragment,
        };
        return write_glsl_reflected(&m, &info, stage, settings);
    }
    let stage = match entry {
        Entry::Fragment => naga::ShaderStage::Fragment,
        _ => naga::ShaderStage::Compute,
    };
    let (text, reflection) = write_glsl(module, info, stage, settings).map_err(|e| err(&e))?;
    let mut blocks: Vec<(u32, String)> = reflection
        .uniforms
        .iter()
        .filter_map(|(h, name)| Some((module.global_variables[*h].binding?.binding, name.clone())))
        .collect();
    // Textures (baked volumes) are uniforms a host binds to a texture unit by name, too.
    blocks.extend(reflection.texture_mapping.iter().filter_map(|(name, m)| {
        Some((
            module.global_variables[m.texture].binding?.binding,
            name.clone(),
        ))
    }));
    blocks.sort();
    Ok((Output::Text(text), Reflection { blocks }))
}

/// A library for SPIR-V or GLSL, which need an entry point: the module with an empty compute
/// `main` (an empty fragment one for GLSL ES 3.00, which has no compute) touching every global,
/// validated; the library functions are written beside it.
fn with_main(
    module: &naga::Module,
    target: Target,
    settings: &Settings,
) -> Result<(naga::Module, ModuleInfo), InternalError> {
    let mut m = module.clone();
    let fragment = target == Target::Glsl && !settings.glsl_version.has_compute();
    let function = touching_globals(&mut m);
    m.entry_points.push(naga::EntryPoint {
        name: "main".into(),
        stage: if fragment {
            naga::ShaderStage::Fragment
        } else {
            naga::ShaderStage::Compute
        },
        early_depth_test: None,
        workgroup_size: if fragment { [0, 0, 0] } else { [1, 1, 1] },
        workgroup_size_overrides: None,
        function,
        mesh_info: None,
        task_payload: None,
        incoming_ray_payload: None,
    });
    let info = validate(&m)?;
    Ok((m, info))
}

/// GLSL of the dialect `settings` asks for, its one entry point `main` of `stage`, and what
/// the writer named.
fn write_glsl(
    module: &naga::Module,
    info: &ModuleInfo,
    stage: naga::ShaderStage,
    settings: &Settings,
) -> Result<(String, back::glsl::ReflectionInfo), back::glsl::Error> {
    let options = back::glsl::Options {
        version: settings.glsl_version.naga(),
        binding_map: glsl_bindings(module),
        ..Default::default()
    };
    let pipeline = back::glsl::PipelineOptions {
        shader_stage: stage,
        entry_point: "main".into(),
        multiview: None,
    };
    let mut s = String::new();
    let reflection = back::glsl::Writer::new(
        &mut s,
        module,
        info,
        &options,
        &pipeline,
        naga::proc::BoundsCheckPolicies::default(),
    )
    .and_then(|mut w| w.write())?;
    Ok((s, reflection))
}
