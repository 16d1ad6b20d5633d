//! The HTML page of the report: the Markdown rendered by pulldown-cmark in a plain page.

use pulldown_cmark::{html, Options, Parser};

/// A standalone HTML page showing `markdown` (images by relative path).
pub fn page(title: &str, markdown: &str) -> String {
    let mut body = String::new();
    html::push_html(&mut body, Parser::new_ext(markdown, Options::ENABLE_TABLES));
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{title}</title>\n<style>\n\
body {{ font-family: sans-serif; max-width: 1100px; margin: 2em auto; padding: 0 1em; line-height: 1.45; }}\n\
table {{ border-collapse: collapse; margin: 1em 0; }}\n\
th, td {{ border: 1px solid #bbb; padding: 0.25em 0.6em; text-align: right; }}\n\
th:first-child, td:first-child {{ text-align: left; }}\n\
img {{ max-width: 100%; image-rendering: pixelated; margin: 0.3em; vertical-align: top; }}\n\
code {{ background: #f2f2f2; padding: 0 0.2em; }}\n\
</style>\n</head>\n<body>\n{body}</body>\n</html>\n"
    )
}
