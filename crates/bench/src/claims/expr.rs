//! The language of a claim: arithmetic over sets of table entries.
//!
//! ```text
//! expr     := compare
//! compare  := sum (("<" | "<=" | ">" | ">=" | "==" | "!=") sum)?
//! sum      := product (("+" | "-") product)*
//! product  := unary (("*" | "/") unary)*
//! unary    := "-" unary | atom
//! atom     := NUMBER | NAME "(" expr ("," expr)* ")" | entries | "(" expr ")"
//! entries  := [DEVICE ":"] NAME ("{" (AXIS "=" VALUE)* "}")?
//! ```
//!
//! `NAME` in `entries` is a table (its JSON's file stem, in the page's device folder or the one
//! `DEVICE:` names) or an alias the page set with `<!--let NAME = entries -->`; the braces pick
//! the entries whose axes have those labels (`photons=2048` or `photons=2048²`,
//! `technique="W&D + Sec. 4"`, `metric=Gather`). A `VALUE` with spaces or braces is quoted.

use anyhow::{bail, Result};

#[derive(Debug, Clone, PartialEq)]
pub enum Expr {
    Num(f64),
    /// A quoted argument: a pass name or a counter (`pass(t{...}, "splat*")`).
    Str(String),
    /// `device:table{axis=value ...}`; `device` is `None` for the page's first folder.
    Entries {
        device: Option<String>,
        name: String,
        pick: Vec<(String, String)>,
    },
    Call(String, Vec<Expr>),
    Neg(Box<Expr>),
    Bin(Op, Box<Expr>, Box<Expr>),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Op {
    Add,
    Sub,
    Mul,
    Div,
    Lt,
    Le,
    Gt,
    Ge,
    Eq,
    Ne,
}

impl Op {
    pub fn symbol(self) -> &'static str {
        match self {
            Op::Add => "+",
            Op::Sub => "-",
            Op::Mul => "*",
            Op::Div => "/",
            Op::Lt => "<",
            Op::Le => "<=",
            Op::Gt => ">",
            Op::Ge => ">=",
            Op::Eq => "==",
            Op::Ne => "!=",
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Num(f64),
    Name(String),
    Str(String),
    Sym(&'static str),
}

const SYMBOLS: [&str; 16] = ["<=", ">=", "==", "!=", "<", ">", "+", "-", "*", "/", "(", ")", "{", "}", ",", ":"];

fn is_name_char(c: char) -> bool {
    c.is_alphanumeric() || matches!(c, '_' | '.' | '²' | '&' | '#')
}

/// Can `label` follow `axis=` without quotes?
pub fn is_bare_label(label: &str) -> bool {
    !label.is_empty() && label.chars().all(is_name_char)
}

fn lex(src: &str) -> Result<Vec<Tok>> {
    let mut out = vec![];
    let chars: Vec<char> = src.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_whitespace() {
            i += 1;
        } else if c == '"' {
            let end = chars[i + 1..].iter().position(|&x| x == '"').map(|p| i + 1 + p);
            let Some(end) = end else { bail!("an unclosed quote in `{src}`") };
            out.push(Tok::Str(chars[i + 1..end].iter().collect()));
            i = end + 1;
        } else if c.is_ascii_digit() {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            let text: String = chars[start..i].iter().collect();
            // A number followed by name characters (`2048²`, `1024x768`) is a label.
            if i < chars.len() && is_name_char(chars[i]) {
                while i < chars.len() && is_name_char(chars[i]) {
                    i += 1;
                }
                out.push(Tok::Name(chars[start..i].iter().collect()));
            } else {
                let v = text.parse().map_err(|_| anyhow::anyhow!("`{text}` is not a number in `{src}`"))?;
                out.push(Tok::Num(v));
            }
        } else if is_name_char(c) {
            let start = i;
            while i < chars.len() && is_name_char(chars[i]) {
                i += 1;
            }
            out.push(Tok::Name(chars[start..i].iter().collect()));
        } else if c == '=' && chars.get(i + 1) != Some(&'=') {
            out.push(Tok::Sym("="));
            i += 1;
        } else {
            let rest: String = chars[i..chars.len().min(i + 2)].iter().collect();
            let Some(s) = SYMBOLS.iter().find(|s| rest.starts_with(**s)) else { bail!("unexpected `{c}` in `{src}`") };
            out.push(Tok::Sym(s));
            i += s.chars().count();
        }
    }
    Ok(out)
}

struct Parser<'a> {
    toks: Vec<Tok>,
    at: usize,
    src: &'a str,
}

impl Parser<'_> {
    fn peek(&self) -> Option<&Tok> {
        self.toks.get(self.at)
    }
    fn eat(&mut self, sym: &str) -> bool {
        if matches!(self.peek(), Some(Tok::Sym(s)) if *s == sym) {
            self.at += 1;
            true
        } else {
            false
        }
    }
    fn expect(&mut self, sym: &str) -> Result<()> {
        if !self.eat(sym) {
            bail!("expected `{sym}` at token {} of `{}`", self.at + 1, self.src);
        }
        Ok(())
    }

    fn compare(&mut self) -> Result<Expr> {
        let left = self.sum()?;
        for (sym, op) in [("<=", Op::Le), (">=", Op::Ge), ("==", Op::Eq), ("!=", Op::Ne), ("<", Op::Lt), (">", Op::Gt)]
        {
            if self.eat(sym) {
                let right = self.sum()?;
                return Ok(Expr::Bin(op, Box::new(left), Box::new(right)));
            }
        }
        Ok(left)
    }

    /// A left-associative level of binary operators over `next` (sums over products, products
    /// over unary terms).
    fn level(&mut self, ops: &[(&str, Op)], next: fn(&mut Self) -> Result<Expr>) -> Result<Expr> {
        let mut e = next(self)?;
        while let Some(&(_, op)) = ops.iter().find(|(sym, _)| self.eat(sym)) {
            e = Expr::Bin(op, Box::new(e), Box::new(next(self)?));
        }
        Ok(e)
    }

    fn sum(&mut self) -> Result<Expr> {
        self.level(&[("+", Op::Add), ("-", Op::Sub)], Self::product)
    }

    fn product(&mut self) -> Result<Expr> {
        self.level(&[("*", Op::Mul), ("/", Op::Div)], Self::unary)
    }

    fn unary(&mut self) -> Result<Expr> {
        if self.eat("-") {
            return Ok(Expr::Neg(Box::new(self.unary()?)));
        }
        self.atom()
    }

    fn value(&mut self) -> Result<String> {
        match self.toks.get(self.at).cloned() {
            Some(Tok::Name(s)) | Some(Tok::Str(s)) => {
                self.at += 1;
                Ok(s)
            }
            Some(Tok::Num(v)) => {
                self.at += 1;
                Ok(format!("{v}"))
            }
            _ => bail!("expected a label after `=` in `{}`", self.src),
        }
    }

    fn atom(&mut self) -> Result<Expr> {
        match self.toks.get(self.at).cloned() {
            Some(Tok::Num(v)) => {
                self.at += 1;
                Ok(Expr::Num(v))
            }
            Some(Tok::Str(s)) => {
                self.at += 1;
                Ok(Expr::Str(s))
            }
            Some(Tok::Sym("(")) => {
                self.at += 1;
                let e = self.compare()?;
                self.expect(")")?;
                Ok(e)
            }
            Some(Tok::Name(name)) => {
                self.at += 1;
                if self.eat("(") {
                    let mut args = vec![self.compare()?];
                    while self.eat(",") {
                        args.push(self.compare()?);
                    }
                    self.expect(")")?;
                    return Ok(Expr::Call(name, args));
                }
                let (device, name) = if self.eat(":") {
                    match self.toks.get(self.at).cloned() {
                        Some(Tok::Name(table)) => {
                            self.at += 1;
                            (Some(name), table)
                        }
                        _ => bail!("expected a table after `{name}:` in `{}`", self.src),
                    }
                } else {
                    (None, name)
                };
                let mut pick = vec![];
                if self.eat("{") {
                    while !self.eat("}") {
                        let axis = match self.toks.get(self.at).cloned() {
                            Some(Tok::Name(a)) => a,
                            _ => bail!("expected `axis=label` or `}}` in `{}`", self.src),
                        };
                        self.at += 1;
                        self.expect("=")?;
                        pick.push((axis, self.value()?));
                    }
                }
                Ok(Expr::Entries { device, name, pick })
            }
            Some(t) => bail!("unexpected {t:?} in `{}`", self.src),
            None => bail!("`{}` ends too soon", self.src),
        }
    }
}

pub fn parse(src: &str) -> Result<Expr> {
    let mut p = Parser { toks: lex(src)?, at: 0, src };
    let e = p.compare()?;
    if p.at != p.toks.len() {
        bail!("unexpected {:?} after the claim in `{src}`", p.toks[p.at]);
    }
    Ok(e)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entries(name: &str, pick: &[(&str, &str)]) -> Expr {
        Expr::Entries {
            device: None,
            name: name.into(),
            pick: pick.iter().map(|(a, v)| (a.to_string(), v.to_string())).collect(),
        }
    }

    #[test]
    fn a_ratio_of_two_picks_parses_with_quoted_and_squared_labels() {
        let e = parse(r#"t3{photons=2048² technique="W&D + Sec. 4"} / t3{photons=2048 metric=Gather}"#).unwrap();
        assert_eq!(
            e,
            Expr::Bin(
                Op::Div,
                Box::new(entries("t3", &[("photons", "2048²"), ("technique", "W&D + Sec. 4")])),
                Box::new(entries("t3", &[("photons", "2048"), ("metric", "Gather")])),
            )
        );
    }

    #[test]
    fn products_bind_tighter_than_sums_and_comparisons_last() {
        let e = parse("1 + 2 * 3 < 8").unwrap();
        let sum = Expr::Bin(
            Op::Add,
            Box::new(Expr::Num(1.0)),
            Box::new(Expr::Bin(Op::Mul, Box::new(Expr::Num(2.0)), Box::new(Expr::Num(3.0)))),
        );
        assert_eq!(e, Expr::Bin(Op::Lt, Box::new(sum), Box::new(Expr::Num(8.0))));
    }

    #[test]
    fn a_device_prefix_and_a_call() {
        let e = parse("range(h100:wyman2008_table1{scene=bunny})").unwrap();
        let Expr::Call(f, args) = e else { panic!("not a call") };
        assert_eq!(f, "range");
        assert_eq!(
            args[0],
            Expr::Entries {
                device: Some("h100".into()),
                name: "wyman2008_table1".into(),
                pick: vec![("scene".into(), "bunny".into())]
            }
        );
    }

    #[test]
    fn broken_claims_are_refused_with_the_text() {
        for bad in ["t3{photons=}", "t3{photons=1", "(1 + 2", "1 2", "\"open", "t3 $ 2"] {
            let err = parse(bad).unwrap_err().to_string();
            assert!(err.contains(bad) || err.contains("quote"), "{bad}: {err}");
        }
    }

    #[test]
    fn each_operator_names_itself_in_messages() {
        let ops = [Op::Add, Op::Sub, Op::Mul, Op::Div, Op::Lt, Op::Le, Op::Gt, Op::Ge, Op::Eq, Op::Ne];
        let symbols: Vec<&str> = ops.iter().map(|o| o.symbol()).collect();
        assert_eq!(symbols, ["+", "-", "*", "/", "<", "<=", ">", ">=", "==", "!="]);
    }

    #[test]
    fn a_bare_label_needs_no_quotes() {
        for bare in ["Gather", "W&D", "2048²", "wd-points".replace('-', "_").as_str(), "Sec.4", "#1"] {
            assert!(is_bare_label(bare), "{bare}");
        }
        for quoted in ["", "W&D + Sec. 4", "wd-points", "a b", "x/y"] {
            assert!(!is_bare_label(quoted), "{quoted}");
        }
    }

    #[test]
    fn names_and_labels_may_end_the_claim_and_equality_is_one_symbol() {
        assert_eq!(parse("t3").unwrap(), entries("t3", &[]));
        assert_eq!(parse("2048²").unwrap(), entries("2048²", &[]));
        assert_eq!(
            parse("t3 == 2").unwrap(),
            Expr::Bin(Op::Eq, Box::new(entries("t3", &[])), Box::new(Expr::Num(2.0)))
        );
        assert_eq!(parse("2!=t3").unwrap(), Expr::Bin(Op::Ne, Box::new(Expr::Num(2.0)), Box::new(entries("t3", &[]))));
    }
}
