//! Prints every marker of every embedded ArUco dictionary as robocal reads
//! it, one line per marker: `name id size bits` (bits row-major, 1 = white).
//! `bench/aruco_dictionary_check.py` compares the lines with OpenCV.
//!
//! cargo run -p robocal-calib --example aruco_dictionary_dump > /tmp/aruco_dump.txt

use robocal_calib::vision::aruco::predefined_all;

fn main() {
    for d in predefined_all() {
        for id in 0..d.len() {
            let bits: String = (0..d.marker_size)
                .flat_map(|r| (0..d.marker_size).map(move |c| (r, c)))
                .map(|(r, c)| if d.bit(id, r, c) { '1' } else { '0' })
                .collect();
            println!("{} {} {} {}", d.name, id, d.marker_size, bits);
        }
    }
}
