//! A small well-formedness checker for the tests: balanced and properly
//! nested tags, quoted attributes, no raw `<` or stray `&` in text or
//! attribute values, a single root element. With `html`, void elements
//! (`<meta>`) need no closing tag and `<style>` content is raw text.

const VOID_ELEMENTS: [&str; 6] = ["meta", "br", "hr", "img", "input", "link"];

fn check_entities(text: &str, at: usize) -> Result<(), String> {
    for (i, _) in text.match_indices('&') {
        let rest = &text[i + 1..];
        let end = rest
            .find(';')
            .ok_or(format!("bare & near byte {}", at + i))?;
        let name = &rest[..end];
        let ok = match name.strip_prefix('#') {
            Some(num) => num
                .strip_prefix('x')
                .map_or(num.parse::<u32>().is_ok(), |h| {
                    u32::from_str_radix(h, 16).is_ok()
                }),
            None => !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric()),
        };
        if !ok {
            return Err(format!("bad entity &{name}; near byte {}", at + i));
        }
    }
    Ok(())
}

/// Splits a tag's inside into its name and checks its attributes.
fn parse_tag(inner: &str, at: usize) -> Result<String, String> {
    let name_end = inner
        .find(|c: char| c.is_whitespace())
        .unwrap_or(inner.len());
    let name = &inner[..name_end];
    if name.is_empty()
        || !name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == ':')
    {
        return Err(format!("bad tag name {name:?} at byte {at}"));
    }
    let mut rest = inner[name_end..].trim_start();
    while !rest.is_empty() {
        let eq = rest
            .find('=')
            .ok_or(format!("attribute without value in <{name}> at byte {at}"))?;
        let attr = rest[..eq].trim();
        if attr.is_empty()
            || !attr
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || "-:_".contains(c))
        {
            return Err(format!("bad attribute {attr:?} in <{name}> at byte {at}"));
        }
        let value_part = rest[eq + 1..].trim_start();
        let quote = value_part
            .chars()
            .next()
            .filter(|q| *q == '"' || *q == '\'');
        let quote = quote.ok_or(format!("unquoted attribute {attr} at byte {at}"))?;
        let close = value_part[1..]
            .find(quote)
            .ok_or(format!("unterminated attribute {attr} at byte {at}"))?;
        let value = &value_part[1..1 + close];
        if value.contains('<') {
            return Err(format!("raw < in attribute {attr} at byte {at}"));
        }
        check_entities(value, at)?;
        rest = value_part[close + 2..].trim_start();
    }
    Ok(name.to_string())
}

/// Ok when `doc` is well formed in the sense above.
pub fn check_balanced(doc: &str, html: bool) -> Result<(), String> {
    let mut stack: Vec<String> = Vec::new();
    let mut roots = 0;
    let mut pos = 0;
    while let Some(offset) = doc[pos..].find('<') {
        let start = pos + offset;
        check_entities(&doc[pos..start], pos)?;
        let rest = &doc[start..];
        let skip_to = |end: &str| {
            rest.find(end)
                .map(|i| start + i + end.len())
                .ok_or(format!("unterminated {end} at {start}"))
        };
        if rest.starts_with("<!--") {
            pos = skip_to("-->")?;
            continue;
        }
        if rest.starts_with("<!") || rest.starts_with("<?") {
            pos = skip_to(">")?;
            continue;
        }
        let end = start
            + rest
                .find('>')
                .ok_or(format!("unterminated tag at byte {start}"))?;
        let inner = &doc[start + 1..end];
        pos = end + 1;
        if let Some(closing) = inner.strip_prefix('/') {
            let open = stack
                .pop()
                .ok_or(format!("</{closing}> without opening tag at byte {start}"))?;
            if open != closing.trim() {
                return Err(format!("<{open}> closed by </{closing}> at byte {start}"));
            }
            continue;
        }
        let self_closing = inner.ends_with('/');
        let name = parse_tag(inner.trim_end_matches('/'), start)?;
        if stack.is_empty() {
            roots += 1;
        }
        if self_closing || (html && VOID_ELEMENTS.contains(&name.as_str())) {
            continue;
        }
        if html && (name == "style" || name == "script") {
            let close = format!("</{name}>");
            pos = pos
                + doc[pos..]
                    .find(&close)
                    .ok_or(format!("unterminated <{name}>"))?
                + close.len();
            continue;
        }
        stack.push(name);
    }
    check_entities(&doc[pos..], pos)?;
    if let Some(open) = stack.pop() {
        return Err(format!("<{open}> never closed"));
    }
    if roots != 1 {
        return Err(format!("{roots} root elements"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::check_balanced;

    #[test]
    fn accepts_well_formed_and_rejects_broken_markup() {
        assert!(check_balanced(
            r#"<?xml version="1.0"?><svg a="1"><g><text>a &amp; b</text></g><line/></svg>"#,
            false
        )
        .is_ok());
        assert!(check_balanced("<svg><g></svg></g>", false).is_err());
        assert!(check_balanced("<svg><g></svg>", false).is_err());
        assert!(check_balanced("<svg>a & b</svg>", false).is_err());
        assert!(check_balanced("<svg>a < b</svg>", false).is_err());
        assert!(check_balanced(r#"<svg a="<"></svg>"#, false).is_err());
        assert!(check_balanced("<svg a=1></svg>", false).is_err());
        assert!(check_balanced("<svg></svg><svg></svg>", false).is_err());
        assert!(check_balanced(
            "<!DOCTYPE html><html><meta charset=\"utf-8\"><style>a > b {}</style></html>",
            true
        )
        .is_ok());
    }
}
