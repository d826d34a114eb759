//! A small typed builder over naga's arenas, so that lowering code reads like the algorithm it
//! emits: expressions are appended and `Emit` ranges managed for the caller; blocks nest through
//! closures (`if_`, `loop_`).

use naga::{
    Arena, BinaryOperator, Block, Expression, Function, FunctionArgument, FunctionResult, Handle,
    Literal, LocalVariable, MathFunction, Module, Scalar, ScalarKind, Span, Statement, Type,
    TypeInner, VectorSize, proc::Emitter,
};

/// An expression handle in the function being built.
pub type Ex = Handle<Expression>;

/// The module under construction, and its helper functions by name.
#[derive(Default)]
pub struct ModuleBuilder {
    /// The module.
    pub module: Module,
    helpers: std::collections::HashMap<String, Handle<Function>>,
    /// The compute entry's count of shading evaluations, if it has one (`lower/count.rs`).
    pub evaluations: Option<Handle<naga::GlobalVariable>>,
    /// Whether that counter counts primitive evaluations instead (`Options::count_primitives`).
    pub primitives: bool,
    /// The `Params` uniform, if the scene has parameters (`lower/params.rs`).
    pub params: Option<Handle<naga::GlobalVariable>>,
    /// Per primitive function (`sd_<name>`), which arguments are constants inside it rather
    /// than parameters (`Primitive::bake`).
    pub baked: std::collections::HashMap<String, Vec<bool>>,
    /// Each baked volume's read function `volume_<i>(p)` (`lower/volumes.rs`).
    pub volumes: Vec<(std::sync::Arc<crate::bake::Volume>, Handle<Function>)>,
}

impl ModuleBuilder {
    /// A helper function added earlier with [`ModuleBuilder::add_helper`].
    pub fn helper(&self, name: &str) -> Handle<Function> {
        *self
            .helpers
            .get(name)
            .unwrap_or_else(|| panic!("helper `{name}` was not added before use"))
    }

    /// The read function of a baked volume (declared before `map` is built).
    pub fn volume_fn(&self, volume: &std::sync::Arc<crate::bake::Volume>) -> Handle<Function> {
        self.volumes
            .iter()
            .find(|(v, _)| std::sync::Arc::ptr_eq(v, volume))
            .map(|(_, f)| *f)
            .expect("every reachable volume declared before `map`")
    }

    /// Whether a helper exists.
    pub fn has_helper(&self, name: &str) -> bool {
        self.helpers.contains_key(name)
    }

    /// Adds a function that later code finds by name.
    pub fn add_helper(&mut self, name: &str, f: Function) -> Handle<Function> {
        let h = self.add_function(f);
        self.helpers.insert(name.to_string(), h);
        h
    }

    /// Interns a type.
    pub fn ty(&mut self, inner: TypeInner) -> Handle<Type> {
        self.module
            .types
            .insert(Type { name: None, inner }, Span::UNDEFINED)
    }

    /// Interns a named type (structs).
    pub fn named_ty(&mut self, name: &str, inner: TypeInner) -> Handle<Type> {
        self.module.types.insert(
            Type {
                name: Some(name.to_string()),
                inner,
            },
            Span::UNDEFINED,
        )
    }

    /// `f32`
    pub fn f32(&mut self) -> Handle<Type> {
        self.ty(TypeInner::Scalar(Scalar::F32))
    }

    /// `u32`
    pub fn u32(&mut self) -> Handle<Type> {
        self.ty(TypeInner::Scalar(Scalar::U32))
    }

    /// `bool`
    pub fn bool(&mut self) -> Handle<Type> {
        self.ty(TypeInner::Scalar(Scalar::BOOL))
    }

    /// `vecN<f32>`
    pub fn vec(&mut self, size: VectorSize) -> Handle<Type> {
        self.ty(TypeInner::Vector {
            size,
            scalar: Scalar::F32,
        })
    }

    /// `vec3<f32>`
    pub fn vec3(&mut self) -> Handle<Type> {
        self.vec(VectorSize::Tri)
    }

    /// `vecN<u32>`
    pub fn uvec(&mut self, size: VectorSize) -> Handle<Type> {
        self.ty(TypeInner::Vector {
            size,
            scalar: Scalar::U32,
        })
    }

    /// Adds a finished function; it must come before its callers.
    pub fn add_function(&mut self, f: Function) -> Handle<Function> {
        self.module.functions.append(f, Span::UNDEFINED)
    }
}

/// Builds one function's body.
pub struct FnBuilder<'m> {
    /// The module the function belongs to (for types and callees).
    pub m: &'m mut ModuleBuilder,
    /// The function so far.
    pub func: Function,
    emitter: Emitter,
    blocks: Vec<Block>,
}

impl<'m> FnBuilder<'m> {
    /// Starts a function with named arguments and an optional result type.
    pub fn new(
        m: &'m mut ModuleBuilder,
        name: &str,
        args: &[(&str, Handle<Type>)],
        result: Option<Handle<Type>>,
    ) -> FnBuilder<'m> {
        let func = Function {
            name: Some(name.to_string()),
            arguments: args
                .iter()
                .map(|(n, ty)| FunctionArgument {
                    name: Some(n.to_string()),
                    ty: *ty,
                    binding: None,
                })
                .collect(),
            result: result.map(|ty| FunctionResult { ty, binding: None }),
            ..Function::default()
        };
        let mut b = FnBuilder {
            m,
            func,
            emitter: Emitter::default(),
            blocks: vec![Block::new()],
        };
        b.emitter.start(&b.func.expressions);
        b
    }

    /// Ends the current `Emit` range into the current block (the emitter stops).
    pub(super) fn pause(&mut self) {
        if let Some((stmt, span)) = self.emitter.finish(&self.func.expressions) {
            self.current().push(stmt, span);
        }
    }

    /// Starts a new `Emit` range at the end of the arena.
    pub(super) fn resume(&mut self) {
        self.emitter.start(&self.func.expressions);
    }

    pub(super) fn current(&mut self) -> &mut Block {
        self.blocks.last_mut().expect("a block is open")
    }

    /// Appends an expression, keeping pre-emitted kinds (literals, arguments, variables) out
    /// of `Emit` ranges as the validator requires.
    pub fn expr(&mut self, e: Expression) -> Ex {
        if e.needs_pre_emit() {
            self.pause();
            let h = self.func.expressions.append(e, Span::UNDEFINED);
            self.resume();
            h
        } else {
            self.func.expressions.append(e, Span::UNDEFINED)
        }
    }

    /// Gives an expression a name, so back ends write `let name = ...`.
    pub fn name(&mut self, e: Ex, name: &str) -> Ex {
        self.func.named_expressions.insert(e, name.to_string());
        e
    }

    /// Pushes a statement after flushing pending expressions.
    pub fn stmt(&mut self, s: Statement) {
        self.pause();
        self.current().push(s, Span::UNDEFINED);
        self.resume();
    }

    /// Argument `i`.
    pub fn arg(&mut self, i: u32) -> Ex {
        self.expr(Expression::FunctionArgument(i))
    }

    /// An f32 literal.
    pub fn f(&mut self, x: f64) -> Ex {
        self.expr(Expression::Literal(Literal::F32(x as f32)))
    }

    /// The value of `e` if it is an f32 literal.
    pub fn literal(&self, e: Ex) -> Option<f64> {
        match self.func.expressions[e] {
            Expression::Literal(Literal::F32(x)) => Some(f64::from(x)),
            _ => None,
        }
    }

    /// A u32 literal.
    pub fn u(&mut self, x: u32) -> Ex {
        self.expr(Expression::Literal(Literal::U32(x)))
    }

    /// A bool literal.
    pub fn boolean(&mut self, x: bool) -> Ex {
        self.expr(Expression::Literal(Literal::Bool(x)))
    }

    /// A `vec3<f32>` of literals.
    pub fn vec3_lit(&mut self, v: glam::DVec3) -> Ex {
        if v.x == v.y && v.y == v.z {
            let s = self.f(v.x);
            return self.splat(s, VectorSize::Tri);
        }
        let c = [self.f(v.x), self.f(v.y), self.f(v.z)];
        self.compose_vec3(c)
    }

    /// `vec3(x, y, z)` of expressions.
    pub fn compose_vec3(&mut self, c: [Ex; 3]) -> Ex {
        let ty = self.m.vec3();
        self.expr(Expression::Compose {
            ty,
            components: c.to_vec(),
        })
    }

    /// Composes a value of type `ty`.
    pub fn compose(&mut self, ty: Handle<Type>, components: Vec<Ex>) -> Ex {
        self.expr(Expression::Compose { ty, components })
    }

    /// A vector of one value repeated.
    pub fn splat(&mut self, value: Ex, size: VectorSize) -> Ex {
        self.expr(Expression::Splat { size, value })
    }

    /// A binary operation.
    pub fn bin(&mut self, op: BinaryOperator, left: Ex, right: Ex) -> Ex {
        self.expr(Expression::Binary { op, left, right })
    }

    /// a + b
    pub fn add(&mut self, a: Ex, b: Ex) -> Ex {
        self.bin(BinaryOperator::Add, a, b)
    }

    /// a − b
    pub fn sub(&mut self, a: Ex, b: Ex) -> Ex {
        self.bin(BinaryOperator::Subtract, a, b)
    }

    /// a · b (componentwise, or scalar × vector)
    pub fn mul(&mut self, a: Ex, b: Ex) -> Ex {
        self.bin(BinaryOperator::Multiply, a, b)
    }

    /// a / b (naga IR has no vector / scalar: multiply by the reciprocal instead)
    pub fn div(&mut self, a: Ex, b: Ex) -> Ex {
        self.bin(BinaryOperator::Divide, a, b)
    }

    /// a < b
    pub fn lt(&mut self, a: Ex, b: Ex) -> Ex {
        self.bin(BinaryOperator::Less, a, b)
    }

    /// a > b
    pub fn gt(&mut self, a: Ex, b: Ex) -> Ex {
        self.bin(BinaryOperator::Greater, a, b)
    }

    /// a ≤ b
    pub fn le(&mut self, a: Ex, b: Ex) -> Ex {
        self.bin(BinaryOperator::LessEqual, a, b)
    }

    /// a ≥ b
    pub fn ge(&mut self, a: Ex, b: Ex) -> Ex {
        self.bin(BinaryOperator::GreaterEqual, a, b)
    }

    /// −a
    pub fn neg(&mut self, a: Ex) -> Ex {
        self.expr(Expression::Unary {
            op: naga::UnaryOperator::Negate,
            expr: a,
        })
    }

    /// a math function of one to three arguments.
    pub fn math(&mut self, fun: MathFunction, args: &[Ex]) -> Ex {
        self.expr(Expression::Math {
            fun,
            arg: args[0],
            arg1: args.get(1).copied(),
            arg2: args.get(2).copied(),
            arg3: None,
        })
    }

    /// `select(reject, accept, condition)`: accept where the condition holds.
    pub fn select(&mut self, condition: Ex, accept: Ex, reject: Ex) -> Ex {
        self.expr(Expression::Select {
            condition,
            accept,
            reject,
        })
    }

    /// Component `i` of a vector or member `i` of a struct.
    pub fn at(&mut self, base: Ex, index: u32) -> Ex {
        self.expr(Expression::AccessIndex { base, index })
    }

    /// A swizzle of a vector (`v.xz` is `[0, 2]`).
    pub fn swizzle(&mut self, vector: Ex, pattern: &[u32]) -> Ex {
        let size = match pattern.len() {
            2 => VectorSize::Bi,
            3 => VectorSize::Tri,
            _ => VectorSize::Quad,
        };
        let mut p = [naga::SwizzleComponent::X; 4];
        for (slot, &c) in p.iter_mut().zip(pattern) {
            *slot = naga::SwizzleComponent::XYZW[c as usize];
        }
        self.expr(Expression::Swizzle {
            size,
            vector,
            pattern: p,
        })
    }

    /// Converts a scalar or vector to another scalar kind (`f32(u)`).
    pub fn cast(&mut self, expr: Ex, kind: ScalarKind) -> Ex {
        self.expr(Expression::As {
            expr,
            kind,
            convert: Some(4),
        })
    }

    /// A local variable, optionally initialised; returns its pointer.
    pub fn local(&mut self, name: &str, ty: Handle<Type>, init: Option<Ex>) -> Ex {
        let var = self.func.local_variables.append(
            LocalVariable {
                name: Some(name.to_string()),
                ty,
                init: None,
            },
            Span::UNDEFINED,
        );
        let ptr = self.expr(Expression::LocalVariable(var));
        if let Some(v) = init {
            self.store(ptr, v);
        }
        ptr
    }

    /// Reads a variable.
    pub fn load(&mut self, pointer: Ex) -> Ex {
        self.expr(Expression::Load { pointer })
    }

    /// Writes a variable.
    pub fn store(&mut self, pointer: Ex, value: Ex) {
        self.stmt(Statement::Store { pointer, value });
    }

    /// Builds a nested block with `body`.
    pub(super) fn block(&mut self, body: impl FnOnce(&mut Self)) -> Block {
        self.pause();
        self.blocks.push(Block::new());
        self.resume();
        body(self);
        self.pause();
        let block = self.blocks.pop().expect("the block pushed above");
        self.resume();
        block
    }

    /// `if condition { accept } else { reject }`
    pub fn if_(
        &mut self,
        condition: Ex,
        accept: impl FnOnce(&mut Self),
        reject: impl FnOnce(&mut Self),
    ) {
        let accept = self.block(accept);
        let reject = self.block(reject);
        self.stmt(Statement::If {
            condition,
            accept,
            reject,
        });
    }

    /// `loop { body }`; leave it with [`FnBuilder::brk`].
    pub fn loop_(&mut self, body: impl FnOnce(&mut Self)) {
        let body = self.block(body);
        self.stmt(Statement::Loop {
            body,
            continuing: Block::new(),
            break_if: None,
        });
    }

    /// `*pointer += 1u` on a u32 variable.
    pub fn increment(&mut self, pointer: Ex) {
        let v = self.load(pointer);
        let one = self.u(1);
        let v1 = self.add(v, one);
        self.store(pointer, v1);
    }

    /// A counted loop: `var name = 0u; loop { if name >= count { break; } body(name); name += 1u; }`,
    /// the body given the index's value. The body may `break` early.
    pub fn repeat(&mut self, name: &str, count: Ex, body: impl FnOnce(&mut Self, Ex)) {
        let u32t = self.m.u32();
        let zero = self.u(0);
        let i = self.local(name, u32t, Some(zero));
        self.loop_(|b| {
            let iv = b.load(i);
            let done = b.ge(iv, count);
            b.break_if(done);
            body(b, iv);
            let one = b.u(1);
            let next = b.add(iv, one);
            b.store(i, next);
        });
    }

    /// `break`
    pub fn brk(&mut self) {
        self.stmt(Statement::Break);
    }

    /// `if condition { break; }`
    pub fn break_if(&mut self, condition: Ex) {
        self.if_(condition, |b| b.brk(), |_| {});
    }

    /// Calls a function; returns its result.
    pub fn call(&mut self, function: Handle<Function>, arguments: Vec<Ex>) -> Ex {
        self.pause();
        let result = self
            .func
            .expressions
            .append(Expression::CallResult(function), Span::UNDEFINED);
        self.current().push(
            Statement::Call {
                function,
                arguments,
                result: Some(result),
            },
            Span::UNDEFINED,
        );
        self.resume();
        result
    }

    /// `return value`
    pub fn ret(&mut self, value: Option<Ex>) {
        self.stmt(Statement::Return { value });
    }

    /// The finished function.
    pub fn finish(mut self) -> Function {
        self.pause();
        let body = self.blocks.pop().expect("the function's block");
        self.func.body = body;
        self.func
    }

    /// The function's expression arena.
    pub fn expressions(&self) -> &Arena<Expression> {
        &self.func.expressions
    }
}
