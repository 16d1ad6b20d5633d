//! A command line as a POSIX shell reads it: each word quoted only if it must be.

/// `word` quoted for a POSIX shell: as is if it holds only characters no shell treats
/// specially, else in single quotes (a `'` inside becomes `'\''`).
pub fn quote(word: &str) -> String {
    let plain = !word.is_empty()
        && word
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "_@%+=:,./-".contains(c));
    if plain {
        word.to_owned()
    } else {
        format!("'{}'", word.replace('\'', r"'\''"))
    }
}

/// The words as one shell command line, preceded by `cd DIR &&` when `cd` is given (the words
/// name files relative to it).
pub fn line(words: &[String], cd: Option<&str>) -> String {
    let command = words.iter().map(|w| quote(w)).collect::<Vec<_>>().join(" ");
    match cd {
        Some(dir) => format!("cd {} && {command}", quote(dir)),
        None => command,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_are_quoted_only_when_they_must_be() {
        assert_eq!(quote("--dem"), "--dem");
        assert_eq!(quote("/tmp/a_b-1.2/x.asc"), "/tmp/a_b-1.2/x.asc");
        assert_eq!(quote(""), "''");
        assert_eq!(quote("my map.asc"), "'my map.asc'");
        assert_eq!(quote("it's"), r"'it'\''s'");
        assert_eq!(quote("$HOME*"), "'$HOME*'");
        let words = ["footprint".to_string(), "a b".to_string()];
        assert_eq!(line(&words, None), "footprint 'a b'");
        assert_eq!(line(&words, Some("/w d")), "cd '/w d' && footprint 'a b'");
    }

    /// The quoted line, read back by `sh`, gives the same words.
    #[test]
    fn sh_reads_back_the_words() {
        let words: Vec<String> = ["a b", "it's", "", "$x", "\"q\"", "tab\there", "ü", "-"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        let script = format!(
            "for w in {}; do printf '%s\\n' \"[$w]\"; done",
            line(&words, None)
        );
        let out = std::process::Command::new("sh")
            .args(["-c", &script])
            .output()
            .expect("sh runs");
        let got = String::from_utf8(out.stdout).unwrap();
        let want: String = words.iter().map(|w| format!("[{w}]\n")).collect();
        assert_eq!(got, want);
    }
}
