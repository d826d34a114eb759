//! Control flow and memory the generic evaluators need beyond `if` and `loop`: a `switch` on a
//! u32, indexing by a run-time value, reinterpreting bits, popping a stack's height, and atomic
//! additions.

use super::builder::{Ex, FnBuilder};
use naga::{Expression, ScalarKind, Span, Statement, SwitchCase, SwitchValue};

/// One arm of a [`FnBuilder::switch_`]: the case's value and what builds its body.
pub type Arm<'f, 'a> = (u32, Box<dyn FnOnce(&mut FnBuilder<'a>) + 'f>);

impl<'a> FnBuilder<'a> {
    /// `switch selector { case v: { body } … default: { default } }` on a u32 selector.
    pub fn switch_(
        &mut self,
        selector: Ex,
        cases: Vec<Arm<'_, 'a>>,
        default: impl FnOnce(&mut Self),
    ) {
        let mut arms = Vec::with_capacity(cases.len() + 1);
        for (value, body) in cases {
            let body = self.block(body);
            arms.push(SwitchCase {
                value: SwitchValue::U32(value),
                body,
                fall_through: false,
            });
        }
        let body = self.block(default);
        arms.push(SwitchCase {
            value: SwitchValue::Default,
            body,
            fall_through: false,
        });
        self.stmt(Statement::Switch {
            selector,
            cases: arms,
        });
    }

    /// `base[index]` with a run-time index: a pointer to the element of an array or a
    /// runtime-sized buffer that `base` points to, or the element of a vector value.
    pub fn index(&mut self, base: Ex, index: Ex) -> Ex {
        self.expr(Expression::Access { base, index })
    }

    /// The same bits as another scalar kind (`bitcast<f32>(u)`), for scalars and vectors.
    pub fn bitcast(&mut self, expr: Ex, kind: ScalarKind) -> Ex {
        self.expr(Expression::As {
            expr,
            kind,
            convert: None,
        })
    }

    /// `*pointer -= 1u` on a u32 variable (a stack's height, popped); the new value.
    pub fn decrement(&mut self, pointer: Ex) -> Ex {
        let v = self.load(pointer);
        let one = self.u(1);
        let v1 = self.sub(v, one);
        self.store(pointer, v1);
        v1
    }

    /// `atomicAdd(pointer, value)` on an `atomic<u32>`: the value it held before.
    pub fn atomic_add(&mut self, pointer: Ex, value: Ex) -> Ex {
        let ty = self.m.u32();
        self.pause();
        let result = self.func.expressions.append(
            Expression::AtomicResult {
                ty,
                comparison: false,
            },
            Span::UNDEFINED,
        );
        self.current().push(
            Statement::Atomic {
                pointer,
                fun: naga::AtomicFunction::Add,
                value,
                result: Some(result),
            },
            Span::UNDEFINED,
        );
        self.resume();
        result
    }
}
