//! Random expressions of every kind of node, for the tests of the printers and the bounds
//! that work on their trees.

use crate::cas::Expr;

/// A small deterministic generator (xorshift), so that a failure names its case.
pub struct Gen(pub u64);

impl Gen {
    pub fn below(&mut self, n: usize) -> usize {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 % n as u64) as usize
    }

    pub fn expr(&mut self, depth: usize) -> Expr {
        let leaf = depth == 0 || self.below(4) == 0;
        if leaf {
            return self.leaf();
        }
        let d = depth - 1;
        let some = |g: &mut Gen, n: usize| (0..n).map(|_| g.expr(d)).collect::<Vec<_>>();
        match self.below(9) {
            0 | 1 => {
                let n = 2 + self.below(3);
                Expr::Add(some(self, n))
            }
            2 | 3 => {
                let n = 2 + self.below(3);
                Expr::Mul(some(self, n))
            }
            4 => {
                let exponent = match self.below(5) {
                    0 => Expr::int(2),
                    1 => Expr::int(-1),
                    2 => Expr::rat(1, 2),
                    3 => Expr::rat(-3, 2),
                    _ => self.expr(d),
                };
                Expr::Pow(Box::new(self.expr(d)), Box::new(exponent))
            }
            5 => {
                let (name, n) = CALLS[self.below(CALLS.len())];
                Expr::Call(name.into(), some(self, n))
            }
            6 => {
                let n = 1 + self.below(3);
                Expr::List(some(self, n))
            }
            7 => {
                let rows = 1 + self.below(3);
                let cols = 1 + self.below(3);
                Expr::List((0..rows).map(|_| Expr::List(some(self, cols))).collect())
            }
            _ => self.indexed(d),
        }
    }

    /// A name, an integer or a fraction.
    fn leaf(&mut self) -> Expr {
        match self.below(3) {
            0 => Expr::Sym(NAMES[self.below(NAMES.len())].into()),
            1 => Expr::int(self.below(40) as i128 - 12),
            _ => Expr::rat(self.below(9) as i128 - 4, 2 + self.below(11) as i128),
        }
    }

    /// A tensor or an expression, indexed once or twice.
    fn indexed(&mut self, d: usize) -> Expr {
        let mut e = if self.below(2) == 0 {
            Expr::Sym("tensor_of".into())
        } else {
            self.expr(d)
        };
        for _ in 0..1 + self.below(2) {
            let i = if self.below(4) == 0 {
                self.expr(d)
            } else {
                Expr::int(self.below(3) as i128)
            };
            e = Expr::Index(Box::new(e), Box::new(i));
        }
        e
    }
}

const NAMES: &[&str] = &[
    "x",
    "m",
    "alpha",
    "phi",
    "mu",
    "w1",
    "wd2",
    "Ixx",
    "phi'",
    "theta''",
    "tensor_of",
    "Om2",
    "I1cone",
    "L",
    "m1",
    "OmE",
    "d2U",
    "R",
];

const CALLS: &[(&str, usize)] = &[
    ("sin", 1),
    ("cos", 1),
    ("sqrt", 1),
    ("acos", 1),
    ("dot", 2),
    ("cross", 2),
    ("outer", 2),
    ("transpose", 1),
    ("eye", 0),
    ("rot_z", 1),
    ("diff", 2),
    ("subs", 3),
    ("atan2", 2),
];
