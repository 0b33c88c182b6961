//! The entry names of a zip archive as its central directory lists them,
//! duplicates included. The `zip` crate keeps one entry per name (the
//! later one wins, silently), so an archive holding two `poses.json` or two
//! images of one name would be read as something other than what other
//! tools extract from it; the dataset reader refuses such archives.

use std::collections::HashSet;
use std::io::{Read, Seek, SeekFrom};

const EOCD_SIGNATURE: u32 = 0x0605_4b50;
const ZIP64_LOCATOR_SIGNATURE: u32 = 0x0706_4b50;
const ZIP64_EOCD_SIGNATURE: u32 = 0x0606_4b50;
const ENTRY_SIGNATURE: u32 = 0x0201_4b50;
/// Fixed part of the end record, and the most its comment can add.
const EOCD_LEN: u64 = 22;
const MAX_COMMENT: u64 = 0xFFFF;
const ZIP64_LOCATOR_LEN: u64 = 20;
/// Fixed part of a central directory entry.
const ENTRY_LEN: usize = 46;
/// Largest central directory read (100,000 entries of long names).
pub const MAX_DIRECTORY_BYTES: u64 = 64 * 1024 * 1024;

/// The first name listed twice, if any. `Ok(None)` also when the directory
/// cannot be found where the end record says (the zip reader then decides).
pub fn first_duplicate<R: Read + Seek>(file: &mut R) -> std::io::Result<Option<String>> {
    let Some((offset, size)) = directory_span(file)? else {
        return Ok(None);
    };
    if size > MAX_DIRECTORY_BYTES {
        return Err(std::io::Error::other(format!(
            "the central directory is {size} bytes; at most {MAX_DIRECTORY_BYTES}"
        )));
    }
    file.seek(SeekFrom::Start(offset))?;
    let mut directory = vec![0u8; size as usize];
    if file.read_exact(&mut directory).is_err() {
        return Ok(None);
    }
    let mut seen = HashSet::new();
    let mut at = 0;
    while at + ENTRY_LEN <= directory.len() && u32_at(&directory, at) == ENTRY_SIGNATURE {
        let name_len = u16_at(&directory, at + 28) as usize;
        let extra_len = u16_at(&directory, at + 30) as usize;
        let comment_len = u16_at(&directory, at + 32) as usize;
        let Some(name) = directory.get(at + ENTRY_LEN..at + ENTRY_LEN + name_len) else {
            break;
        };
        let name = String::from_utf8_lossy(name).into_owned();
        if !seen.insert(name.clone()) {
            return Ok(Some(name));
        }
        at += ENTRY_LEN + name_len + extra_len + comment_len;
    }
    Ok(None)
}

/// Offset and size of the central directory, from the end record (zip64 too).
fn directory_span<R: Read + Seek>(file: &mut R) -> std::io::Result<Option<(u64, u64)>> {
    let len = file.seek(SeekFrom::End(0))?;
    let tail_len = len.min(EOCD_LEN + MAX_COMMENT + ZIP64_LOCATOR_LEN);
    file.seek(SeekFrom::Start(len - tail_len))?;
    let mut tail = vec![0u8; tail_len as usize];
    file.read_exact(&mut tail)?;
    let Some(end) = (0..tail.len().saturating_sub(EOCD_LEN as usize - 1))
        .rev()
        .find(|&i| u32_at(&tail, i) == EOCD_SIGNATURE)
    else {
        return Ok(None);
    };
    let size = u32_at(&tail, end + 12) as u64;
    let offset = u32_at(&tail, end + 16) as u64;
    if size != u32::MAX as u64 && offset != u32::MAX as u64 {
        return Ok(Some((offset, size)));
    }
    let Some(locator) = end.checked_sub(ZIP64_LOCATOR_LEN as usize) else {
        return Ok(None);
    };
    if u32_at(&tail, locator) != ZIP64_LOCATOR_SIGNATURE {
        return Ok(None);
    }
    let record = u64_at(&tail, locator + 8);
    let mut head = [0u8; 56];
    file.seek(SeekFrom::Start(record))?;
    if file.read_exact(&mut head).is_err() || u32_at(&head, 0) != ZIP64_EOCD_SIGNATURE {
        return Ok(None);
    }
    Ok(Some((u64_at(&head, 48), u64_at(&head, 40))))
}

fn u16_at(b: &[u8], at: usize) -> u16 {
    u16::from_le_bytes([b[at], b[at + 1]])
}

fn u32_at(b: &[u8], at: usize) -> u32 {
    b.get(at..at + 4)
        .map_or(0, |s| u32::from_le_bytes([s[0], s[1], s[2], s[3]]))
}

fn u64_at(b: &[u8], at: usize) -> u64 {
    b.get(at..at + 8).map_or(0, |s| {
        u64::from_le_bytes([s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7]])
    })
}

#[cfg(test)]
mod tests {
    use std::io::{Cursor, Write};

    use super::*;

    fn archive(names: &[&str]) -> Vec<u8> {
        let mut out = Cursor::new(Vec::new());
        {
            let mut zip = zip::ZipWriter::new(&mut out);
            let options = zip::write::SimpleFileOptions::default();
            for name in names {
                zip.start_file(*name, options).unwrap();
                zip.write_all(name.as_bytes()).unwrap();
            }
            zip.finish().unwrap();
        }
        out.into_inner()
    }

    #[test]
    fn a_name_listed_twice_is_found() {
        let once = archive(&["poses.json", "a.png", "b.png"]);
        assert_eq!(first_duplicate(&mut Cursor::new(once)).unwrap(), None);
        // The writer refuses duplicates: rename one entry in the bytes.
        let mut twice = archive(&["poses.json", "a.png", "b.png"]);
        for i in 0..twice.len() - 5 {
            if &twice[i..i + 5] == b"b.png" {
                twice[i] = b'a';
            }
        }
        assert_eq!(
            first_duplicate(&mut Cursor::new(twice)).unwrap().as_deref(),
            Some("a.png")
        );
    }
}
