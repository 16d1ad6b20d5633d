//! Numbers as people read them: counts with thousands separators (`1,325,513`).

/// `n` with a `,` between groups of three digits: `5432` as `5,432`, `-12345` as `-12,345`.
pub fn thousands(n: impl Into<i128>) -> String {
    let n: i128 = n.into();
    let digits = n.unsigned_abs().to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3 + 1);
    if n < 0 {
        out.push('-');
    }
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// `n` with its sign always shown and thousands separators: `+1,234`, `-5`, `+0`.
pub fn signed_thousands(n: impl Into<i128>) -> String {
    let n: i128 = n.into();
    if n < 0 {
        thousands(n)
    } else {
        format!("+{}", thousands(n))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_of_three() {
        assert_eq!(thousands(0u64), "0");
        assert_eq!(thousands(999u64), "999");
        assert_eq!(thousands(1000u64), "1,000");
        assert_eq!(thousands(1_325_513u64), "1,325,513");
        assert_eq!(thousands(-12_345i64), "-12,345");
        assert_eq!(thousands(u64::MAX), "18,446,744,073,709,551,615");
        assert_eq!(signed_thousands(0i64), "+0");
        assert_eq!(signed_thousands(2_044i64), "+2,044");
        assert_eq!(signed_thousands(-621i64), "-621");
    }
}
