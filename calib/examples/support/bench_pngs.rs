//! PNGs and truth of the rendered detector benches (`chessboard_bench`,
//! `charuco_bench`, issue 14): a rendering run writes them, `--from` reads
//! them back, and the OpenCV scripts in `bench/` read the same files.

use std::collections::HashMap;
use std::fmt::Write as _;

use robocal_calib::sim::render::TruthDot;
use robocal_calib::vision::GrayImage;

/// First line of `truth.csv`.
pub const TRUTH_HEADER: &str = "image,id,row,col,x,y,visible\n";

/// Writes `image` as `out/name`, 8-bit as a camera gives it, appends its
/// truth rows to `csv` and returns the 8-bit image (what the benches time).
pub fn save_view(
    out: &str,
    name: &str,
    image: &GrayImage,
    truth: &[TruthDot],
    csv: &mut String,
) -> image::GrayImage {
    let png = image.to_luma8();
    png.save(format!("{out}/{name}")).expect("write png");
    for (id, t) in truth.iter().enumerate() {
        let _ = writeln!(
            csv,
            "{name},{id},{},{},{:.6},{:.6},{}",
            t.row,
            t.col,
            t.x,
            t.y,
            u8::from(t.visible)
        );
    }
    png
}

/// The truth of an earlier run's `truth.csv`, by image (ids in order).
pub fn read_truth(dir: &str) -> HashMap<String, Vec<TruthDot>> {
    let text = std::fs::read_to_string(format!("{dir}/truth.csv")).expect("truth.csv");
    let mut out: HashMap<String, Vec<TruthDot>> = HashMap::new();
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        out.entry(f[0].to_string()).or_default().push(TruthDot {
            row: f[2].parse().expect("row"),
            col: f[3].parse().expect("col"),
            x: f[4].parse().expect("x"),
            y: f[5].parse().expect("y"),
            visible: f[6] == "1",
        });
    }
    out
}

/// Where a bench's views come from: an earlier run's directory and truth
/// (`--from`), or a fresh render written to `out` with its truth in `csv`.
pub enum Views<'a> {
    Read {
        dir: &'a str,
        truth: &'a HashMap<String, Vec<TruthDot>>,
    },
    Render {
        out: &'a str,
        csv: &'a mut String,
    },
}

impl Views<'_> {
    /// The 8-bit image of view `name` (as a decoder gives it, what OpenCV
    /// is given) and its truth; `render` is called only when rendering.
    pub fn get(
        &mut self,
        name: &str,
        render: impl FnOnce() -> (GrayImage, Vec<TruthDot>),
    ) -> (image::GrayImage, Vec<TruthDot>) {
        match self {
            Views::Read { dir, truth } => {
                let img = image::open(format!("{dir}/{name}")).expect("read png");
                (img.to_luma8(), truth[name].clone())
            }
            Views::Render { out, csv } => {
                let (image, truth) = render();
                (save_view(out, name, &image, &truth, csv), truth)
            }
        }
    }
}
