//! Expressions compiled once for many evaluations along a motion: the scene's values folded
//! in as constants, each state name (a coordinate, rate or acceleration) a slot of a slice, and
//! one register per distinct subexpression. Each register computes what [`Expr::eval`] computes
//! for its node, the same operations in the same order, so the values are the same to the last
//! bit, and a check's figures do not move.

use crate::cas::{EvalError, Expr};
use std::collections::BTreeMap;

/// One register's operation; its operands are earlier registers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Op {
    Const(u64),
    Slot(usize),
    Add,
    Mul,
    PowI(i32),
    PowF,
    Sin,
    Cos,
    Sqrt,
    Acos,
    Exp,
    Log,
    Atan,
    Atan2,
    Sinh,
    Cosh,
    Abs,
    Asin,
}

/// A register: its operation and its operands' range in `Program::operands`.
#[derive(Debug, Clone, Copy)]
struct Instr {
    op: Op,
    from: u32,
    len: u32,
}

/// Expressions ready to evaluate at a slice of state values: one register per distinct
/// subexpression (a subexpression met twice is computed once), subexpressions of constants
/// computed while compiling, and each expression's value in an output register.
#[derive(Debug, Clone)]
pub struct Program {
    instrs: Vec<Instr>,
    operands: Vec<u32>,
    outputs: Vec<u32>,
    /// The registers that read a slot at or after `varying_from`, in order: all that must be
    /// computed again when only those slots change.
    varying: Vec<u32>,
}

impl Program {
    /// `exprs` with each name of `slots` read from the slice at its index, `pi` the number, and
    /// every other name its value in `params` (an error where it has none, as `eval` gives).
    /// Slots from `varying_from` on may change alone ([`Program::eval_varying`]).
    pub fn new(
        exprs: &[&Expr],
        slots: &BTreeMap<String, usize>,
        params: &BTreeMap<String, f64>,
        varying_from: usize,
    ) -> Result<Program, EvalError> {
        let mut b = Builder {
            slots,
            params,
            program: Program {
                instrs: Vec::new(),
                operands: Vec::new(),
                outputs: Vec::new(),
                varying: Vec::new(),
            },
            seen: std::collections::HashMap::new(),
            varies: Vec::new(),
            varying_from,
        };
        for e in exprs {
            let r = b.emit(e)?;
            b.program.outputs.push(r);
        }
        b.program.varying = (0..b.varies.len() as u32)
            .filter(|&r| b.varies[r as usize])
            .collect();
        Ok(b.program)
    }

    /// Every output at `x`; `registers` is scratch space, kept for [`Program::eval_varying`].
    pub fn eval(&self, x: &[f64], registers: &mut Vec<f64>) -> Vec<f64> {
        // Every register is written before it is read: no need to clear them.
        registers.resize(self.instrs.len(), 0.0);
        for r in 0..self.instrs.len() {
            registers[r] = self.compute(r, x, registers);
        }
        self.outputs
            .iter()
            .map(|&r| registers[r as usize])
            .collect()
    }

    /// Every output at `x`, where `registers` hold a full [`Program::eval`] at a point that
    /// differs from `x` only in the varying slots.
    pub fn eval_varying(&self, x: &[f64], registers: &mut [f64]) -> Vec<f64> {
        for &r in &self.varying {
            registers[r as usize] = self.compute(r as usize, x, registers);
        }
        self.outputs
            .iter()
            .map(|&r| registers[r as usize])
            .collect()
    }

    /// Register r from its operands.
    fn compute(&self, r: usize, x: &[f64], registers: &[f64]) -> f64 {
        let Instr { op, from, len } = self.instrs[r];
        let args = &self.operands[from as usize..(from + len) as usize];
        apply(op, args.len(), |k| registers[args[k] as usize], x)
    }
}

/// One operation on its operands' values (`value(k)` is the k-th), as `Expr::eval` computes
/// its node: the same operations in the same order.
fn apply(op: Op, len: usize, value: impl Fn(usize) -> f64, x: &[f64]) -> f64 {
    match op {
        Op::Const(bits) => f64::from_bits(bits),
        Op::Slot(i) => x[i],
        Op::Add => (0..len).map(value).sum(),
        Op::Mul => (0..len).map(value).product(),
        Op::PowI(k) => value(0).powi(k),
        Op::PowF => value(0).powf(value(1)),
        Op::Sin => value(0).sin(),
        Op::Cos => value(0).cos(),
        Op::Sqrt => value(0).sqrt(),
        Op::Acos => value(0).acos(),
        Op::Asin => value(0).asin(),
        Op::Exp => value(0).exp(),
        Op::Log => value(0).ln(),
        Op::Atan => value(0).atan(),
        Op::Atan2 => value(0).atan2(value(1)),
        Op::Sinh => value(0).sinh(),
        Op::Cosh => value(0).cosh(),
        Op::Abs => value(0).abs(),
    }
}

struct Builder<'a> {
    slots: &'a BTreeMap<String, usize>,
    params: &'a BTreeMap<String, f64>,
    program: Program,
    /// Each distinct (operation, operands) and its register.
    seen: std::collections::HashMap<(Op, Vec<u32>), u32>,
    /// Whether each register reads a varying slot.
    varies: Vec<bool>,
    varying_from: usize,
}

impl Builder<'_> {
    /// The register of `e`, its parts emitted first in `Expr::eval`'s order.
    fn emit(&mut self, e: &Expr) -> Result<u32, EvalError> {
        let constant = |v: f64| (Op::Const(v.to_bits()), Vec::new());
        let (op, args) = match e {
            Expr::Num(r) => constant(r.to_f64()),
            Expr::Sym(s) if s == "pi" => constant(std::f64::consts::PI),
            Expr::Sym(s) => match (self.slots.get(s), self.params.get(s)) {
                (Some(&i), _) => (Op::Slot(i), Vec::new()),
                (None, Some(&v)) => constant(v),
                (None, None) => return Err(EvalError::NoValue(s.clone())),
            },
            Expr::Add(v) | Expr::Mul(v) => {
                let args = v.iter().map(|x| self.emit(x)).collect::<Result<_, _>>()?;
                let op = if matches!(e, Expr::Add(_)) {
                    Op::Add
                } else {
                    Op::Mul
                };
                (op, args)
            }
            Expr::Pow(a, b) => {
                let base = self.emit(a)?;
                match b.as_ref() {
                    Expr::Num(r) if r.to_i64().is_some_and(|k| k.unsigned_abs() < 64) => {
                        (Op::PowI(r.to_i64().unwrap_or(1) as i32), vec![base])
                    }
                    other => (Op::PowF, vec![base, self.emit(other)?]),
                }
            }
            Expr::Call(name, args) if crate::cas::arity(name) == Some(args.len()) => {
                let op = match name.as_str() {
                    "sin" => Op::Sin,
                    "cos" => Op::Cos,
                    "sqrt" => Op::Sqrt,
                    "acos" => Op::Acos,
                    "asin" => Op::Asin,
                    "exp" => Op::Exp,
                    "log" => Op::Log,
                    "atan" => Op::Atan,
                    "atan2" => Op::Atan2,
                    "sinh" => Op::Sinh,
                    "cosh" => Op::Cosh,
                    "abs" => Op::Abs,
                    _ => return Err(EvalError::NotScalarFunction(name.clone())),
                };
                let xs = args
                    .iter()
                    .map(|a| self.emit(a))
                    .collect::<Result<_, _>>()?;
                (op, xs)
            }
            Expr::Call(name, _) => return Err(EvalError::NotScalarFunction(name.clone())),
            Expr::List(_) | Expr::Index(..) => return Err(EvalError::NotScalar),
        };
        Ok(self.register(op, args))
    }

    /// The register computing `op` of `args`: one already made, or a constant when every
    /// operand is one (computed now, by the same arithmetic), or a new one.
    fn register(&mut self, op: Op, args: Vec<u32>) -> u32 {
        let constant = |r: &u32| match self.program.instrs[*r as usize].op {
            Op::Const(bits) => Some(f64::from_bits(bits)),
            _ => None,
        };
        let values: Option<Vec<f64>> = args.iter().map(constant).collect();
        let (op, args) = match values {
            Some(values) if !matches!(op, Op::Const(_) | Op::Slot(_)) => {
                let v = apply(op, values.len(), |k| values[k], &[]);
                (Op::Const(v.to_bits()), Vec::new())
            }
            _ => (op, args),
        };
        if let Some(&r) = self.seen.get(&(op, args.clone())) {
            return r;
        }
        let varies = match op {
            Op::Slot(i) => i >= self.varying_from,
            _ => args.iter().any(|&a| self.varies[a as usize]),
        };
        let from = self.program.operands.len() as u32;
        self.program.operands.extend(&args);
        self.program.instrs.push(Instr {
            op,
            from,
            len: args.len() as u32,
        });
        self.varies.push(varies);
        let r = (self.program.instrs.len() - 1) as u32;
        self.seen.insert((op, args), r);
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The compiled form gives `Expr::eval`'s value bit for bit, at many points, on an
    /// expression with every operation; an unbound name is the same error.
    #[test]
    fn compiled_values_are_evals_to_the_bit() {
        let e = crate::cas::parse(
            "m*l^2*(2*x'^2 + x'*y'*cos(x - y)) + m*g*l*cos(x)/3 - sqrt(k)*sin(y)^3 \
             + (x^2 + 1)^(1/3) + pi*acos(y/9) + asin(x/9) + m*l^2*(2*x'^2 + x'*y'*cos(x - y))",
        )
        .unwrap()
        .expr;
        let params: BTreeMap<String, f64> =
            [("m", 1.5), ("l", 0.7), ("g", 9.81), ("k", 2.0), ("x", 99.0)]
                .into_iter()
                .map(|(k, v)| (k.to_string(), v))
                .collect();
        let slots: BTreeMap<String, usize> = [("x", 0), ("y", 1), ("x'", 2), ("y'", 3)]
            .into_iter()
            .map(|(k, v)| (k.to_string(), v))
            .collect();
        let compiled = Program::new(&[&e], &slots, &params, usize::MAX).unwrap();
        let mut registers = Vec::new();
        let mut rng = crate::base::rng::Rng::new(7);
        for _ in 0..1000 {
            let x: Vec<f64> = (0..4).map(|_| 6.0 * rng.uniform() - 3.0).collect();
            let mut point = params.clone();
            for (name, &i) in &slots {
                point.insert(name.clone(), x[i]);
            }
            let want = e.eval(&|s| point.get(s).copied()).unwrap();
            let got = compiled.eval(&x, &mut registers)[0];
            assert_eq!(got.to_bits(), want.to_bits(), "{x:?}: {got} {want}");
        }
        let unbound = crate::cas::parse("x + z").unwrap().expr;
        assert_eq!(
            Program::new(&[&unbound], &slots, &params, usize::MAX).err(),
            Some(EvalError::NoValue("z".into()))
        );
    }

    /// Two residuals sharing subexpressions, in one program: after one full evaluation, moving
    /// only the accelerations (the varying slots) and evaluating those registers alone gives
    /// the full evaluation's values to the bit; a register per distinct subexpression, and
    /// none for a subexpression of constants.
    #[test]
    fn varying_slots_alone_give_the_full_evaluation() {
        let r1 = crate::cas::parse(
            "m*l^2*(2*x'' + y''*cos(x - y)) + m*l^2*y'^2*sin(x - y) + m*g*l*sin(x)",
        )
        .unwrap()
        .expr;
        let r2 = crate::cas::parse(
            "m*l^2*(y'' + x''*cos(x - y)) - m*l^2*x'^2*sin(x - y) + m*g*l*sin(y)",
        )
        .unwrap()
        .expr;
        let params: BTreeMap<String, f64> = [("m", 1.5), ("l", 0.7), ("g", 9.81)]
            .into_iter()
            .map(|(k, v)| (k.to_string(), v))
            .collect();
        let names = ["x", "y", "x'", "y'", "x''", "y''"];
        let slots: BTreeMap<String, usize> = names
            .iter()
            .enumerate()
            .map(|(i, k)| (k.to_string(), i))
            .collect();
        let program = Program::new(&[&r1, &r2], &slots, &params, 4).unwrap();
        // m*l^2 folds to one constant; cos(x - y) and sin(x - y) are computed once.
        let cosines = program.instrs.iter().filter(|i| i.op == Op::Cos).count();
        assert_eq!(cosines, 1);
        assert!(
            program.varying.len() < program.instrs.len() / 2,
            "{program:?}"
        );
        let mut rng = crate::base::rng::Rng::new(3);
        let mut registers = Vec::new();
        for _ in 0..200 {
            let mut x: Vec<f64> = (0..6).map(|_| 4.0 * rng.uniform() - 2.0).collect();
            program.eval(&x, &mut registers);
            x[4] = rng.uniform();
            x[5] = rng.uniform();
            let partial = program.eval_varying(&x, &mut registers);
            let full = program.eval(&x, &mut Vec::new());
            let point: BTreeMap<String, f64> = params
                .iter()
                .map(|(k, v)| (k.clone(), *v))
                .chain(names.iter().map(|k| (k.to_string(), x[slots[*k]])))
                .collect();
            for (k, e) in [&r1, &r2].iter().enumerate() {
                let want = e.eval(&|s| point.get(s).copied()).unwrap();
                assert_eq!(partial[k].to_bits(), want.to_bits());
                assert_eq!(full[k].to_bits(), want.to_bits());
            }
        }
    }
}
