//! How the readers' messages write numbers: digits grouped in threes.

/// `n` with commas between groups of three digits: `-1,234,567`.
pub fn grouped(n: i64) -> String {
    let digits = grouped_u64(n.unsigned_abs());
    if n < 0 {
        format!("-{digits}")
    } else {
        digits
    }
}

/// `n` with commas between groups of three digits: `1,234,567`.
pub fn grouped_u64(n: u64) -> String {
    let s = n.to_string();
    let mut out = String::with_capacity(s.len() + s.len() / 3);
    for (i, c) in s.chars().enumerate() {
        if i > 0 && (s.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}
