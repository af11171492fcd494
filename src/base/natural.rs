//! Natural order: runs of digits compared as numbers, so that `week-6` comes before `week-10`
//! and lecture `9` before lecture `10`; equal numbers with different zeros, and everything
//! else, fall back to the plain order of the text.

use std::cmp::Ordering;

/// `a` against `b` in natural order.
pub fn compare(a: &str, b: &str) -> Ordering {
    let (mut x, mut y) = (a, b);
    loop {
        match (x.chars().next(), y.chars().next()) {
            (None, None) => return a.cmp(b),
            (None, Some(_)) => return Ordering::Less,
            (Some(_), None) => return Ordering::Greater,
            (Some(c), Some(d)) if c.is_ascii_digit() && d.is_ascii_digit() => {
                let (m, rest_x) = digits(x);
                let (n, rest_y) = digits(y);
                let (m, n) = (m.trim_start_matches('0'), n.trim_start_matches('0'));
                let by_value = m.len().cmp(&n.len()).then_with(|| m.cmp(n));
                if by_value != Ordering::Equal {
                    return by_value;
                }
                (x, y) = (rest_x, rest_y);
            }
            (Some(c), Some(d)) => {
                if c != d {
                    return c.cmp(&d);
                }
                (x, y) = (&x[c.len_utf8()..], &y[d.len_utf8()..]);
            }
        }
    }
}

fn digits(s: &str) -> (&str, &str) {
    let end = s.find(|c: char| !c.is_ascii_digit()).unwrap_or(s.len());
    s.split_at(end)
}

#[cfg(test)]
mod tests {
    use super::compare;
    use std::cmp::Ordering::*;

    #[test]
    fn numbers_in_text_compare_by_value() {
        let mut weeks = [
            "week-10", "week-6", "week-9", "week-1", "3/9", "3/4", "3/10",
        ];
        weeks.sort_by(|a, b| compare(a, b));
        assert_eq!(
            weeks,
            [
                "3/4", "3/9", "3/10", "week-1", "week-6", "week-9", "week-10"
            ]
        );
        assert_eq!(compare("05-cube", "05b-cube"), Less);
        assert_eq!(compare("01-a", "1-a"), "01-a".cmp("1-a"));
        assert_eq!(compare("a", "a"), Equal);
        assert_eq!(compare("x2", "x"), Greater);
        // A run of digits longer than any integer type.
        assert_eq!(
            compare("a99999999999999999999999", "a100000000000000000000000"),
            Less
        );
    }
}
