//! Pose labels: what a cell engineer calls a pose, so a line of the report
//! can be traced back to its photo. An uploaded image's file name (only its
//! last path component: the client's directories are no concern of ours),
//! or the `label` a JSON pose sends.

/// Longest label kept, characters. File names beyond this are cut (the
/// end is kept: numbered shots differ in their last characters).
pub const MAX_LABEL_CHARS: usize = 200;

/// What a label may be, as told to clients.
pub const LABEL_RULE: &str = "1 to 200 characters, no control characters";

/// The label of an uploaded file: its base name, without control
/// characters, cut to [`MAX_LABEL_CHARS`]; `None` when nothing is left.
pub fn label_from_file_name(file_name: &str) -> Option<String> {
    let base = file_name.rsplit(['/', '\\']).next().unwrap_or(file_name);
    label_from_archive_path(base)
}

/// The label of an image inside a dataset archive: its whole path there
/// (`day2/0001.png` and `day1/0001.png` stay apart), cleaned and cut like
/// [`label_from_file_name`].
pub fn label_from_archive_path(path: &str) -> Option<String> {
    let clean: String = path.chars().filter(|c| !c.is_control()).collect();
    let clean = clean.trim();
    let count = clean.chars().count();
    let kept: String = clean
        .chars()
        .skip(count.saturating_sub(MAX_LABEL_CHARS))
        .collect();
    (!kept.is_empty()).then_some(kept)
}

/// A label sent by a client: accepted as is when it follows [`LABEL_RULE`].
pub fn check_label(label: &str) -> Result<(), &'static str> {
    let count = label.chars().count();
    if (1..=MAX_LABEL_CHARS).contains(&count) && !label.chars().any(char::is_control) {
        Ok(())
    } else {
        Err(LABEL_RULE)
    }
}

/// The label a report shows: the stored one, or the pose's 1-based number
/// in upload order.
pub fn label_or_number(label: Option<&str>, index: usize) -> String {
    match label {
        Some(l) if !l.is_empty() => l.to_string(),
        _ => format!("#{}", index + 1),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn file_names_lose_directories_and_control_characters() {
        assert_eq!(
            label_from_file_name("C:\\shots\\day1/pose_07.png").as_deref(),
            Some("pose_07.png")
        );
        assert_eq!(
            label_from_file_name("a\u{7}b.png").as_deref(),
            Some("ab.png")
        );
        assert_eq!(label_from_file_name("dir/"), None);
        let long = format!("{}_0042.png", "x".repeat(300));
        let kept = label_from_file_name(&long).unwrap();
        assert_eq!(kept.chars().count(), MAX_LABEL_CHARS);
        assert!(kept.ends_with("_0042.png"));
    }

    #[test]
    fn client_labels_are_checked_and_numbers_fill_in() {
        assert!(check_label("shot 7").is_ok());
        assert!(check_label("").is_err());
        assert!(check_label("a\nb").is_err());
        assert!(check_label(&"x".repeat(MAX_LABEL_CHARS + 1)).is_err());
        assert_eq!(label_or_number(None, 11), "#12");
        assert_eq!(label_or_number(Some("p.png"), 0), "p.png");
    }
}
