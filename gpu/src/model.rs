//! A CPU model of what WGSL lets a conforming GPU change, for the bounds in `docs/gpu.md`.
//!
//! The WGSL source itself is evaluated, not a second transcription: naga parses
//! `shaders/warpcore.wgsl` and [`Interpreter`] walks naga's IR of each function in `f32`
//! arithmetic. Without deviations ([`Deviations::NONE`]) every operation is the correctly
//! rounded IEEE one, so the interpreter must return the crate's bits (a check of the
//! transcription that needs no GPU; `tests/model.rs`). With [`Deviations::WGSL`] it applies,
//! operation by operation, what the WGSL specification's accuracy rules allow a GPU to do
//! (section "Floating Point Accuracy"):
//!
//! * `x / y` within 2.5 ulp: the correctly rounded quotient moved by up to 2 ulp either way;
//! * `sqrt(x)`, specified as inherited from `1.0 / inverseSqrt(x)` (2 ulp, then a 2.5-ulp
//!   division): the correctly rounded root moved by up to 4 ulp either way;
//! * fusion: `a * b + c` and `c + a * b` (and the differences) may be evaluated with one
//!   rounding, like `fma`;
//! * reassociation: `(a + b) + c` may become `a + (b + c)` (and the same for differences and
//!   products), except across a fence (`wci_fence` is a bitcast, which no rule may see through).
//!
//! Each choice is drawn at random per operation and point (half of the moves at the extremes
//! of the allowed range), over several trials per point: the result is the largest deviation
//! seen, a measurement under the model, not a proof of a bound. [`Deviations::WGSL_FLUSH`]
//! adds flushing subnormals to zero (allowed by WGSL, done by the NVIDIA H200's Vulkan
//! driver): every subnormal operand and result of an arithmetic operation, comparison or
//! `sqrt` becomes a zero of its sign (bitcasts and selects pass values unchanged, as on the
//! device). Not modelled: errors of GPU float-to-int conversion of out-of-range values (the
//! library converts only in-range values).

use naga::{
    BinaryOperator as B, Expression as E, Handle, Literal, MathFunction, ScalarKind, Statement as S,
};
use std::collections::HashMap;

/// A value of the interpreted program.
#[derive(Clone, Debug)]
pub enum Val {
    F(f32),
    U(u32),
    I(i32),
    B(bool),
    /// A vector or a struct.
    C(Vec<Val>),
    /// A pointer to a local variable.
    P(usize),
    /// A pointer to a member (a path of indices) of a local variable.
    Q(usize, Vec<usize>),
}

/// Component `i` of a vector (a scalar is its own component: WGSL's scalar-vector operands).
fn lane(v: &Val, i: usize) -> Val {
    match v {
        Val::C(c) => c[i].clone(),
        s => s.clone(),
    }
}

fn at_path<'a>(mut v: &'a mut Val, path: &[usize]) -> &'a mut Val {
    for &i in path {
        v = match v {
            Val::C(c) => &mut c[i],
            other => panic!("member of {other:?}"),
        };
    }
    v
}

/// Which deviations the interpreter applies.
#[derive(Clone, Copy, Debug)]
pub struct Deviations {
    /// Largest move of a quotient, in ulps of the correctly rounded result.
    pub div_ulps: u32,
    /// Largest move of a square root, in ulps of the correctly rounded result.
    pub sqrt_ulps: u32,
    /// Fuse multiply-add pairs.
    pub fuse: bool,
    /// Reassociate sums, differences and products.
    pub reassociate: bool,
    /// Flush subnormal operands and results of arithmetic, comparisons and `sqrt` to zero
    /// (of the same sign), as devices that flush do (the H200's Vulkan driver does).
    pub flush: bool,
}

impl Deviations {
    /// IEEE f32 arithmetic, correctly rounded, as the crate computes.
    pub const NONE: Deviations = Deviations {
        div_ulps: 0,
        sqrt_ulps: 0,
        fuse: false,
        reassociate: false,
        flush: false,
    };
    /// What the WGSL accuracy rules allow (see the module docs).
    pub const WGSL: Deviations = Deviations {
        div_ulps: 2,
        sqrt_ulps: 4,
        fuse: true,
        reassociate: true,
        flush: false,
    };
    /// [`Deviations::WGSL`] on a device that flushes subnormals.
    pub const WGSL_FLUSH: Deviations = Deviations {
        flush: true,
        ..Deviations::WGSL
    };
}

/// Walks naga's IR of a module's functions on the CPU.
pub struct Interpreter<'m> {
    module: &'m naga::Module,
    by_name: HashMap<String, Handle<naga::Function>>,
    dev: Deviations,
    rng: u64,
    /// `WARPCORE_MODEL_TRACE_NAN=1`: print where a NaN first arises from non-NaN operands.
    trace_nan: bool,
}

enum Flow {
    Next,
    Break,
    Continue,
    Return(Option<Val>),
}

struct Frame {
    vals: Vec<Option<Val>>,
    locals: Vec<Val>,
    args: Vec<Val>,
}

fn lit(l: &Literal) -> Val {
    match *l {
        Literal::F32(x) => Val::F(x),
        Literal::U32(x) => Val::U(x),
        Literal::I32(x) => Val::I(x),
        Literal::Bool(x) => Val::B(x),
        Literal::AbstractInt(x) => Val::I(x as i32),
        Literal::AbstractFloat(x) => Val::F(x as f32),
        ref other => panic!("literal {other:?} is not used by the library"),
    }
}

/// `x`, or a zero of its sign where `x` is subnormal.
fn flushed(x: f32) -> f32 {
    if x != 0.0 && x.abs() < f32::MIN_POSITIVE {
        0.0f32.copysign(x)
    } else {
        x
    }
}

/// `x` moved by `k` steps on the ordered line of f32 values (finite results only).
/// Zero stays zero (`0 / y`, `sqrt(0)`: every GPU returns an exact zero there).
fn step(x: f32, k: i32) -> f32 {
    if k == 0 || !x.is_finite() || x == 0.0 {
        return x;
    }
    let ord = |b: u32| {
        if b >> 31 == 0 {
            b as i64
        } else {
            -((b & 0x7fff_ffff) as i64)
        }
    };
    let o = ord(x.to_bits()) + k as i64;
    let y = if o >= 0 {
        f32::from_bits(o as u32)
    } else {
        f32::from_bits((-o) as u32 | 0x8000_0000)
    };
    if y.is_finite() { y } else { x }
}

impl<'m> Interpreter<'m> {
    pub fn new(module: &'m naga::Module, dev: Deviations, seed: u64) -> Self {
        let by_name = module
            .functions
            .iter()
            .filter_map(|(h, f)| f.name.clone().map(|n| (n, h)))
            .collect();
        Interpreter {
            module,
            by_name,
            dev,
            rng: seed | 1,
            trace_nan: std::env::var("WARPCORE_MODEL_TRACE_NAN").is_ok_and(|v| v == "1"),
        }
    }

    fn next(&mut self) -> u64 {
        // xorshift64*
        self.rng ^= self.rng >> 12;
        self.rng ^= self.rng << 25;
        self.rng ^= self.rng >> 27;
        self.rng.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// `x` as the device holds it: [`flushed`] where the deviations flush subnormals.
    fn flush(&self, x: f32) -> f32 {
        if self.dev.flush { flushed(x) } else { x }
    }

    fn coin(&mut self) -> bool {
        self.next() >> 63 == 1
    }

    /// A move in `-max..=max` ulps, half of them at the extremes.
    fn ulps(&mut self, max: u32) -> i32 {
        if max == 0 {
            return 0;
        }
        let r = self.next();
        let m = max as i64;
        let k = if r & 1 == 0 {
            if r & 2 == 0 { m } else { -m }
        } else {
            ((r >> 8) % (2 * m as u64 + 1)) as i64 - m
        };
        k as i32
    }

    /// Calls the function `name` with `args` (values in the WGSL parameter order).
    pub fn call(&mut self, name: &str, args: Vec<Val>) -> Val {
        let h = *self
            .by_name
            .get(name)
            .unwrap_or_else(|| panic!("no function {name}"));
        self.call_fn(h, args).expect("the function returns a value")
    }

    /// Builds the argument values of `name` from input words (f32 bits or u32s, flattened).
    /// `func`'s output words on every point of `input` (the random choices continue).
    pub fn outputs(&mut self, func: &crate::Func, input: &[u32]) -> Vec<u32> {
        let mut got = Vec::with_capacity(input.len() / func.in_words() * func.out_words());
        for p in input.chunks_exact(func.in_words()) {
            let args = self.args_from_words(&func.name, p);
            let v = self.call(&func.name, args);
            to_words(&v, &mut got);
        }
        got
    }

    pub fn args_from_words(&self, name: &str, words: &[u32]) -> Vec<Val> {
        let f = &self.module.functions[self.by_name[name]];
        let mut it = words.iter().copied();
        f.arguments
            .iter()
            .map(|a| self.arg_from_words(a.ty, &mut it))
            .collect()
    }

    fn arg_from_words(&self, ty: Handle<naga::Type>, it: &mut impl Iterator<Item = u32>) -> Val {
        let scalar = |s: naga::Scalar, w: u32| match s.kind {
            ScalarKind::Float => Val::F(f32::from_bits(w)),
            ScalarKind::Uint => Val::U(w),
            ScalarKind::Sint => Val::I(w as i32),
            ScalarKind::Bool => Val::B(w != 0),
            _ => panic!("argument kind"),
        };
        match self.module.types[ty].inner {
            naga::TypeInner::Scalar(s) => scalar(s, it.next().unwrap()),
            naga::TypeInner::Vector { size, scalar: s } => Val::C(
                (0..size as usize)
                    .map(|_| scalar(s, it.next().unwrap()))
                    .collect(),
            ),
            ref other => panic!("argument type {other:?}"),
        }
    }

    fn call_fn(&mut self, h: Handle<naga::Function>, args: Vec<Val>) -> Option<Val> {
        let f = &self.module.functions[h];
        let mut fr = Frame {
            vals: vec![None; f.expressions.len()],
            locals: vec![Val::U(0); f.local_variables.len()],
            args,
        };
        for (lh, lv) in f.local_variables.iter() {
            let v = match lv.init {
                Some(init) => self.eval(f, &mut fr, init),
                None => self.zero(lv.ty),
            };
            fr.locals[lh.index()] = v;
        }
        match self.block(f, &mut fr, &f.body) {
            Flow::Return(v) => v,
            _ => None,
        }
    }

    fn block(&mut self, f: &naga::Function, fr: &mut Frame, b: &naga::Block) -> Flow {
        for st in b.iter() {
            let flow = match st {
                S::Emit(range) => {
                    for h in range.clone() {
                        let v = self.compute(f, fr, h);
                        fr.vals[h.index()] = Some(v);
                    }
                    Flow::Next
                }
                S::Block(b) => self.block(f, fr, b),
                S::If {
                    condition,
                    accept,
                    reject,
                } => match self.eval(f, fr, *condition) {
                    Val::B(true) => self.block(f, fr, accept),
                    Val::B(false) => self.block(f, fr, reject),
                    v => panic!("if on {v:?}"),
                },
                S::Loop {
                    body,
                    continuing,
                    break_if,
                } => loop {
                    match self.block(f, fr, body) {
                        Flow::Break => break Flow::Next,
                        Flow::Return(v) => break Flow::Return(v),
                        Flow::Next | Flow::Continue => {}
                    }
                    match self.block(f, fr, continuing) {
                        Flow::Return(v) => break Flow::Return(v),
                        Flow::Break => break Flow::Next,
                        _ => {}
                    }
                    if let Some(c) = break_if
                        && matches!(self.eval(f, fr, *c), Val::B(true))
                    {
                        break Flow::Next;
                    }
                },
                S::Break => Flow::Break,
                S::Continue => Flow::Continue,
                S::Return { value } => Flow::Return(value.map(|v| self.eval(f, fr, v))),
                S::Store { pointer, value } => {
                    let v = self.eval(f, fr, *value);
                    match self.eval(f, fr, *pointer) {
                        Val::P(l) => fr.locals[l] = v,
                        Val::Q(l, path) => *at_path(&mut fr.locals[l], &path) = v,
                        p => panic!("store to {p:?}"),
                    }
                    Flow::Next
                }
                S::Call {
                    function,
                    arguments,
                    result,
                } => {
                    let args = arguments.iter().map(|a| self.eval(f, fr, *a)).collect();
                    let r = self.call_fn(*function, args);
                    if let (Some(h), Some(v)) = (result, r) {
                        fr.vals[h.index()] = Some(v);
                    }
                    Flow::Next
                }
                other => panic!("statement {other:?} is not used by the library"),
            };
            if !matches!(flow, Flow::Next) {
                return flow;
            }
        }
        Flow::Next
    }

    fn eval(&mut self, f: &naga::Function, fr: &mut Frame, h: Handle<E>) -> Val {
        if let Some(v) = &fr.vals[h.index()] {
            return v.clone();
        }
        self.compute(f, fr, h)
    }

    fn global(&self, h: Handle<E>) -> Val {
        match &self.module.global_expressions[h] {
            E::Literal(l) => lit(l),
            E::Constant(c) => self.global(self.module.constants[*c].init),
            E::Compose { components, .. } => {
                Val::C(components.iter().map(|c| self.global(*c)).collect())
            }
            other => panic!("global expression {other:?}"),
        }
    }

    fn zero_scalar(&self, s: naga::Scalar) -> Val {
        match s.kind {
            ScalarKind::Float => Val::F(0.0),
            ScalarKind::Uint => Val::U(0),
            ScalarKind::Sint => Val::I(0),
            _ => Val::B(false),
        }
    }

    fn zero(&self, ty: Handle<naga::Type>) -> Val {
        match self.module.types[ty].inner {
            naga::TypeInner::Scalar(s) => match s.kind {
                ScalarKind::Float => Val::F(0.0),
                ScalarKind::Uint => Val::U(0),
                ScalarKind::Sint => Val::I(0),
                _ => Val::B(false),
            },
            naga::TypeInner::Vector { size, scalar } => {
                let z = self.zero_scalar(scalar);
                Val::C(vec![z; size as usize])
            }
            naga::TypeInner::Struct { ref members, .. } => {
                Val::C(members.iter().map(|m| self.zero(m.ty)).collect())
            }
            ref other => panic!("zero of {other:?}"),
        }
    }

    fn compute(&mut self, f: &naga::Function, fr: &mut Frame, h: Handle<E>) -> Val {
        match &f.expressions[h] {
            E::Literal(l) => lit(l),
            E::Constant(c) => self.global(self.module.constants[*c].init),
            E::ZeroValue(ty) => self.zero(*ty),
            E::Compose { ty, components } => {
                let parts: Vec<Val> = components.iter().map(|c| self.eval(f, fr, *c)).collect();
                if matches!(self.module.types[*ty].inner, naga::TypeInner::Vector { .. }) {
                    // vec4(v3, w) and the like: vector components are spread.
                    Val::C(
                        parts
                            .into_iter()
                            .flat_map(|p| match p {
                                Val::C(c) => c,
                                s => vec![s],
                            })
                            .collect(),
                    )
                } else {
                    Val::C(parts)
                }
            }
            E::AccessIndex { base, index } => match self.eval(f, fr, *base) {
                Val::C(v) => v[*index as usize].clone(),
                Val::P(l) => Val::Q(l, vec![*index as usize]),
                Val::Q(l, mut path) => {
                    path.push(*index as usize);
                    Val::Q(l, path)
                }
                other => panic!("access into {other:?}"),
            },
            E::Splat { size, value } => {
                let v = self.eval(f, fr, *value);
                Val::C(vec![v; *size as usize])
            }
            E::Swizzle {
                size,
                vector,
                pattern,
            } => {
                let v = self.eval(f, fr, *vector);
                Val::C(
                    pattern[..*size as usize]
                        .iter()
                        .map(|c| lane(&v, *c as usize))
                        .collect(),
                )
            }
            E::Relational { fun, argument } => match (fun, self.eval(f, fr, *argument)) {
                (naga::RelationalFunction::All, Val::C(c)) => {
                    Val::B(c.iter().all(|b| matches!(b, Val::B(true))))
                }
                (naga::RelationalFunction::Any, Val::C(c)) => {
                    Val::B(c.iter().any(|b| matches!(b, Val::B(true))))
                }
                (fun, v) => panic!("{fun:?} of {v:?}"),
            },
            E::FunctionArgument(i) => fr.args[*i as usize].clone(),
            E::LocalVariable(l) => Val::P(l.index()),
            E::Load { pointer } => match self.eval(f, fr, *pointer) {
                Val::P(l) => fr.locals[l].clone(),
                Val::Q(l, path) => at_path(&mut fr.locals[l], &path).clone(),
                other => panic!("load from {other:?}"),
            },
            E::Unary { op, expr } => match (op, self.eval(f, fr, *expr)) {
                (naga::UnaryOperator::Negate, Val::C(c)) => Val::C(
                    c.into_iter()
                        .map(|v| match v {
                            Val::F(x) => Val::F(-x),
                            v => panic!("negate {v:?}"),
                        })
                        .collect(),
                ),
                (naga::UnaryOperator::Negate, Val::F(x)) => Val::F(-x),
                (naga::UnaryOperator::Negate, Val::I(x)) => Val::I(x.wrapping_neg()),
                (naga::UnaryOperator::BitwiseNot, Val::U(x)) => Val::U(!x),
                (naga::UnaryOperator::LogicalNot, Val::B(x)) => Val::B(!x),
                (op, v) => panic!("{op:?} {v:?}"),
            },
            E::Binary { op, left, right } => {
                let e = Binary {
                    op: *op,
                    left: *left,
                    right: *right,
                };
                self.binary(f, fr, e)
            }
            E::Select {
                condition,
                accept,
                reject,
            } => match self.eval(f, fr, *condition) {
                Val::B(c) => {
                    let (a, r) = (self.eval(f, fr, *accept), self.eval(f, fr, *reject));
                    if c { a } else { r }
                }
                v => panic!("select on {v:?}"),
            },
            E::Math {
                fun: MathFunction::Sqrt,
                arg,
                ..
            } => match self.eval(f, fr, *arg) {
                Val::F(x) => {
                    let k = self.ulps(self.dev.sqrt_ulps);
                    let x = self.flush(x);
                    if self.trace_nan && x < 0.0 {
                        eprintln!("NaN: {:?} sqrt({x:e})", f.name);
                    }
                    Val::F(self.flush(step(libm::sqrtf(x), k)))
                }
                v => panic!("sqrt of {v:?}"),
            },
            E::Math {
                fun: MathFunction::ReverseBits,
                arg,
                ..
            } => match self.eval(f, fr, *arg) {
                Val::U(x) => Val::U(x.reverse_bits()),
                v => panic!("reverseBits of {v:?}"),
            },
            E::As {
                expr,
                kind,
                convert,
            } => {
                let v = self.eval(f, fr, *expr);
                Self::convert(*convert, *kind, v)
            }
            E::CallResult(_) => panic!("call result read before the call"),
            other => panic!("expression {other:?} is not used by the library"),
        }
    }

    fn convert(convert: Option<u8>, kind: ScalarKind, v: Val) -> Val {
        {
            {
                if let Val::C(c) = v {
                    return Val::C(
                        c.into_iter()
                            .map(|x| Self::convert(convert, kind, x))
                            .collect(),
                    );
                }
                match (convert, kind, v) {
                    (None, ScalarKind::Float, Val::U(x)) => Val::F(f32::from_bits(x)),
                    (None, ScalarKind::Float, Val::I(x)) => Val::F(f32::from_bits(x as u32)),
                    (None, ScalarKind::Uint, Val::F(x)) => Val::U(x.to_bits()),
                    (None, ScalarKind::Uint, Val::I(x)) => Val::U(x as u32),
                    (None, ScalarKind::Sint, Val::U(x)) => Val::I(x as i32),
                    (None, ScalarKind::Sint, Val::F(x)) => Val::I(x.to_bits() as i32),
                    (Some(_), ScalarKind::Float, Val::I(x)) => Val::F(x as f32),
                    (Some(_), ScalarKind::Float, Val::U(x)) => Val::F(x as f32),
                    (Some(_), ScalarKind::Sint, Val::F(x)) => Val::I(x as i32),
                    (Some(_), ScalarKind::Uint, Val::F(x)) => Val::U(x as u32),
                    (Some(_), ScalarKind::Uint, Val::I(x)) => Val::U(x as u32),
                    (Some(_), ScalarKind::Sint, Val::U(x)) => Val::I(x as i32),
                    (c, k, v) => panic!("as {c:?} {k:?} {v:?}"),
                }
            }
        }
    }

    /// The float operands of `h` if it is `a op b` with `op` in `ops`.
    fn float_pair(
        &mut self,
        f: &naga::Function,
        fr: &mut Frame,
        h: Handle<E>,
        ops: &[B],
        at: Option<usize>,
    ) -> Option<(B, f32, f32)> {
        if let E::Binary { op, left, right } = f.expressions[h]
            && ops.contains(&op)
        {
            let (l, r) = (self.eval(f, fr, left), self.eval(f, fr, right));
            let (l, r) = match at {
                Some(i) => (lane(&l, i), lane(&r, i)),
                None => (l, r),
            };
            if let (Val::F(a), Val::F(b)) = (l, r) {
                return Some((op, self.flush(a), self.flush(b)));
            }
        }
        None
    }

    fn binary(&mut self, f: &naga::Function, fr: &mut Frame, e: Binary) -> Val {
        let (l, r) = (self.eval(f, fr, e.left), self.eval(f, fr, e.right));
        let n = match (&l, &r) {
            (Val::C(c), _) | (_, Val::C(c)) => c.len(),
            _ => return self.binary_vals(f, fr, e, l, r, None),
        };
        // Vectors (and scalar-vector operands) lane by lane, with the deviations per lane.
        Val::C(
            (0..n)
                .map(|i| self.binary_vals(f, fr, e, lane(&l, i), lane(&r, i), Some(i)))
                .collect(),
        )
    }

    fn binary_vals(
        &mut self,
        f: &naga::Function,
        fr: &mut Frame,
        e: Binary,
        l: Val,
        r: Val,
        at: Option<usize>,
    ) -> Val {
        let op = e.op;
        match (l, r) {
            (Val::F(a), Val::F(b)) => {
                let (a, b) = (self.flush(a), self.flush(b));
                match comparison(op, a, b) {
                    Some(c) => Val::B(c),
                    None => {
                        let r = self.float_op(f, fr, e, a, b, at);
                        if self.trace_nan && r.is_nan() && !a.is_nan() && !b.is_nan() {
                            eprintln!("NaN: {:?} {a:e} {:?} {b:e}", f.name, e.op);
                        }
                        Val::F(self.flush(r))
                    }
                }
            }
            (Val::U(a), Val::U(b)) => match op {
                B::Add => Val::U(a.wrapping_add(b)),
                B::Subtract => Val::U(a.wrapping_sub(b)),
                B::Multiply => Val::U(a.wrapping_mul(b)),
                B::And => Val::U(a & b),
                B::InclusiveOr => Val::U(a | b),
                B::ExclusiveOr => Val::U(a ^ b),
                B::ShiftLeft => Val::U(a.wrapping_shl(b)),
                B::ShiftRight => Val::U(a.wrapping_shr(b)),
                op => Val::B(comparison(op, a, b).unwrap_or_else(|| panic!("u32 {op:?}"))),
            },
            (Val::B(a), Val::B(b)) => match op {
                B::And | B::LogicalAnd => Val::B(a & b),
                B::InclusiveOr | B::LogicalOr => Val::B(a | b),
                op => Val::B(comparison(op, a, b).unwrap_or_else(|| panic!("bool {op:?}"))),
            },
            (l, r) => panic!("{l:?} {op:?} {r:?}"),
        }
    }

    fn float_op(
        &mut self,
        f: &naga::Function,
        fr: &mut Frame,
        e: Binary,
        a: f32,
        b: f32,
        at: Option<usize>,
    ) -> f32 {
        let (d, Binary { op, left, right }) = (self.dev, e);
        match op {
            B::Add | B::Subtract => {
                let sub = op == B::Subtract;
                let plain = if sub { a - b } else { a + b };
                // Fusion: a product operand rounded together with the sum.
                if d.fuse && self.coin() {
                    if let Some((_, x, y)) = self.float_pair(f, fr, left, &[B::Multiply], at) {
                        let c = if sub { -(b as f64) } else { b as f64 };
                        return ((x as f64) * (y as f64) + c) as f32;
                    }
                    if let Some((_, x, y)) = self.float_pair(f, fr, right, &[B::Multiply], at) {
                        let p = (x as f64) * (y as f64);
                        return (a as f64 + if sub { -p } else { p }) as f32;
                    }
                }
                if d.reassociate && self.coin() {
                    // (x o y) +- b  ->  x o (y o' b)
                    if let Some((inner, x, y)) =
                        self.float_pair(f, fr, left, &[B::Add, B::Subtract], at)
                    {
                        return match (inner, sub) {
                            (B::Add, false) => x + (y + b),
                            (B::Add, true) => x + (y - b),
                            (_, false) => x - (y - b),
                            (_, true) => x - (y + b),
                        };
                    }
                    // a +- (x o y)  ->  (a +- x) o' y
                    if let Some((inner, x, y)) =
                        self.float_pair(f, fr, right, &[B::Add, B::Subtract], at)
                    {
                        return match (sub, inner) {
                            (false, B::Add) => (a + x) + y,
                            (false, _) => (a + x) - y,
                            (true, B::Add) => (a - x) - y,
                            (true, _) => (a - x) + y,
                        };
                    }
                }
                plain
            }
            B::Multiply => {
                if d.reassociate && self.coin() {
                    if let Some((_, x, y)) = self.float_pair(f, fr, left, &[B::Multiply], at) {
                        return x * (y * b);
                    }
                    if let Some((_, x, y)) = self.float_pair(f, fr, right, &[B::Multiply], at) {
                        return (a * x) * y;
                    }
                }
                a * b
            }
            B::Divide => {
                let k = self.ulps(d.div_ulps);
                step(a / b, k)
            }
            _ => panic!("f32 {op:?}"),
        }
    }
}

/// A binary expression `left op right` of the function being interpreted.
#[derive(Clone, Copy)]
struct Binary {
    op: B,
    left: Handle<E>,
    right: Handle<E>,
}

/// A comparison `op` of two values, or `None` where `op` is not a comparison.
fn comparison<T: PartialOrd>(op: B, a: T, b: T) -> Option<bool> {
    Some(match op {
        B::Equal => a == b,
        B::NotEqual => a != b,
        B::Less => a < b,
        B::LessEqual => a <= b,
        B::Greater => a > b,
        B::GreaterEqual => a >= b,
        _ => return None,
    })
}

/// Flattens a returned value into words (f32 bits and u32s), in the harness's output order.
pub fn to_words(v: &Val, out: &mut Vec<u32>) {
    match v {
        Val::F(x) => out.push(x.to_bits()),
        Val::U(x) => out.push(*x),
        Val::I(x) => out.push(*x as u32),
        Val::B(x) => out.push(u32::from(*x)),
        Val::C(c) => c.iter().for_each(|v| to_words(v, out)),
        Val::P(_) | Val::Q(..) => panic!("pointer result"),
    }
}

/// The points whose outputs `got` (`func`'s output words, as [`Interpreter::outputs`] returns
/// them) hold a NaN or infinite float (integer outputs aside).
pub fn nonfinite(func: &crate::Func, got: &[u32]) -> Vec<usize> {
    let outw = func.out_words();
    got.chunks_exact(outw)
        .enumerate()
        .filter(|(_, g)| {
            (0..outw).any(|j| !func.is_integer_output(j) && !f32::from_bits(g[j]).is_finite())
        })
        .map(|(p, _)| p)
        .collect()
}

/// The largest deviation of the interpreted WGSL from the crate for `func` over `input`
/// (`trials` evaluations per point with fresh random choices).
pub fn deviation(
    module: &naga::Module,
    func: &crate::Func,
    input: &[u32],
    dev: Deviations,
    trials: u32,
    seed: u64,
) -> crate::Diff {
    let want = crate::cpu_outputs(func, input);
    let mut interp = Interpreter::new(module, dev, seed);
    let mut total = crate::Diff::default();
    for _ in 0..trials {
        let got = interp.outputs(func, input);
        let d = crate::compare(func, &got, &want);
        total.points += d.points;
        total.mismatches += d.mismatches;
        if d.max_abs > total.max_abs {
            total.max_abs = d.max_abs;
            total.worst = d.worst;
        }
        total.max_ulp = total.max_ulp.max(d.max_ulp);
        if total.first.is_none() {
            total.first = d.first;
        }
    }
    total
}
