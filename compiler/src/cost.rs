//! What a module costs a GPU driver to compile: its shape once every call is inlined, as the
//! drivers do, and the compile time predicted from it (the fit in `docs/stability.md`).

/// Seconds of lavapipe's compile per unit of each term of [`Inlined`] (see [`predict`]): a
/// least-squares fit of the relative error over 24 scenes that took 0.2–43 s to compile
/// (`scripts/compile_cost.py`: flat and smooth unions with and without box trees, materials,
/// shared `let`s, long implicit sums of sines, twisted parts and every example; Mesa 25.0.7 on
/// two cores, its shader cache off).
const PER_SQUARE: f64 = 1.93e-8;
const PER_CHAIN: f64 = 6.49e-6;
const PER_BRANCH_PAIR: f64 = 2.68e-5;
const PER_TRANSCENDENTAL_PAIR: f64 = 4.10e-6;

/// The most a scene's compile took against [`predict`] in that corpus: the upper end of a
/// prediction.
pub const FIT_RATIO: f64 = 2.3;

/// Longest predicted compile (its upper end, seconds) `render`, `bench` and `view` hand to the
/// driver without `--allow-slow-compile`.
pub const MAX_COMPILE_SECONDS: f64 = 30.0;

/// The driver's compile predicted for a module.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Predicted {
    /// The fit's seconds on lavapipe.
    pub seconds: f64,
    /// The upper end: `seconds` × [`FIT_RATIO`].
    pub at_most: f64,
}

impl Predicted {
    /// Whether the upper end passes [`MAX_COMPILE_SECONDS`].
    pub fn too_slow(&self) -> bool {
        self.at_most > MAX_COMPILE_SECONDS
    }
}

/// lavapipe's compile time predicted from the inlined shape: quadratic in each loop body's
/// size (LLVM's passes over one long block), in the chains of `min`/`max` (a union's), in
/// the branches (a box tree's nested tests, executed under masks) and in the transcendental
/// functions. llvmpipe's GL compile took at most as long on the same corpus.
pub fn predict(i: &Inlined) -> Predicted {
    let seconds = PER_SQUARE * i.squares
        + PER_CHAIN * i.chains
        + PER_BRANCH_PAIR * (i.branches as f64).powi(2)
        + PER_TRANSCENDENTAL_PAIR * (i.transcendental as f64).powi(2);
    Predicted {
        seconds,
        at_most: seconds * FIT_RATIO,
    }
}

/// [`predict`] of [`inlined`].
pub fn predict_module(module: &naga::Module) -> Predicted {
    predict(&inlined(module))
}

/// A module's entry point as the driver compiles it, after inlining every call. Mesa
/// (lavapipe, llvmpipe) inlines every function into the entry point before LLVM sees it, so
/// a `map` called from seven places is compiled seven times; each count here counts it so.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Inlined {
    /// Expressions and statements.
    pub size: u64,
    /// Calls (each a function's body written out at its call).
    pub calls: u64,
    /// Branches: `if`s, loops and switches.
    pub branches: u64,
    /// Transcendental functions (sine, exponential, power…): each is a long polynomial with a
    /// range reduction in the driver's code.
    pub transcendental: u64,
    /// Expressions and statements outside every loop.
    pub flat: u64,
    /// The sum of the squares of each loop body's size (outside its inner loops), and of the
    /// entry point's `flat` once the entry is complete ([`inlined`]).
    pub squares: f64,
    /// The sum over the functions written out of the square of their chained minima and
    /// maxima (a `min` or `max` of another's result).
    pub chains: f64,
}

impl std::ops::Add for Inlined {
    type Output = Inlined;
    fn add(self, o: Inlined) -> Inlined {
        Inlined {
            size: self.size + o.size,
            calls: self.calls + o.calls,
            branches: self.branches + o.branches,
            transcendental: self.transcendental + o.transcendental,
            flat: self.flat + o.flat,
            squares: self.squares + o.squares,
            chains: self.chains + o.chains,
        }
    }
}

impl std::iter::Sum for Inlined {
    fn sum<I: Iterator<Item = Inlined>>(iter: I) -> Inlined {
        iter.fold(Inlined::default(), |a, b| a + b)
    }
}

/// The largest entry point of `module` after inlining.
pub fn inlined(module: &naga::Module) -> Inlined {
    // naga's validator keeps a function's callees before it in the arena, so one pass in
    // handle order sees every callee before its callers.
    let mut sizes: Vec<Inlined> = Vec::with_capacity(module.functions.len());
    for (_, f) in module.functions.iter() {
        let size = function(f, &sizes);
        sizes.push(size);
    }
    module
        .entry_points
        .iter()
        .map(|e| {
            let mut i = function(&e.function, &sizes);
            i.squares += (i.flat as f64).powi(2);
            i
        })
        .max_by_key(|i| i.size)
        .unwrap_or_default()
}

/// A function's own expressions (those its statements emit) and statements, each call
/// counted with its callee's
/// (`sizes`, by handle index).
fn function(f: &naga::Function, sizes: &[Inlined]) -> Inlined {
    use naga::MathFunction as M;
    let transcendental = f
        .expressions
        .iter()
        .filter(|(_, e)| {
            matches!(
                e,
                naga::Expression::Math {
                    fun: M::Sin
                        | M::Cos
                        | M::Tan
                        | M::Asin
                        | M::Acos
                        | M::Atan
                        | M::Atan2
                        | M::Sinh
                        | M::Cosh
                        | M::Tanh
                        | M::Exp
                        | M::Exp2
                        | M::Log
                        | M::Log2
                        | M::Pow,
                    ..
                }
            )
        })
        .count() as u64;
    let extremum = |h: naga::Handle<naga::Expression>| {
        matches!(
            f.expressions[h],
            naga::Expression::Math {
                fun: M::Min | M::Max,
                ..
            }
        )
    };
    let chained = f
        .expressions
        .iter()
        .filter(|(_, e)| match e {
            naga::Expression::Math {
                fun: M::Min | M::Max,
                arg,
                arg1: Some(arg1),
                ..
            } => extremum(*arg) || extremum(*arg1),
            _ => false,
        })
        .count();
    let own = Inlined {
        chains: (chained as f64).powi(2),
        transcendental,
        ..Inlined::default()
    };
    own + block(&f.body, sizes)
}

fn block(b: &naga::Block, sizes: &[Inlined]) -> Inlined {
    use naga::Statement as S;
    let one = |calls, branches| Inlined {
        size: 1,
        flat: 1,
        calls,
        branches,
        ..Inlined::default()
    };
    b.iter()
        .map(|s| match s {
            S::Emit(range) => {
                let n = range.clone().count() as u64;
                Inlined {
                    size: n,
                    flat: n,
                    ..Inlined::default()
                }
            }
            S::Call { function, .. } => {
                one(1, 0) + sizes.get(function.index()).copied().unwrap_or_default()
            }
            S::Block(b) => block(b, sizes),
            S::If { accept, reject, .. } => one(0, 1) + block(accept, sizes) + block(reject, sizes),
            S::Loop {
                body, continuing, ..
            } => {
                let mut inside = block(body, sizes) + block(continuing, sizes);
                inside.squares += (inside.flat as f64).powi(2);
                inside.flat = 0;
                one(0, 1) + inside
            }
            S::Switch { cases, .. } => {
                one(0, 1) + cases.iter().map(|c| block(&c.body, sizes)).sum()
            }
            _ => one(0, 0),
        })
        .sum()
}
