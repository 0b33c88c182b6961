use robocal_calib::vision::*;
fn main() {
    let path = std::env::args().nth(1).unwrap();
    let bytes = std::fs::read(path).unwrap();
    let img = ::image::load_from_memory(&bytes).unwrap();
    let t = std::time::Instant::now();
    for _ in 0..100 {
        let d = detect_dynamic(&img, &TargetSpec::robocal_9x9()).unwrap();
        assert_eq!(d.dots.len(), 81);
    }
    println!("{:?} per image", t.elapsed() / 100);
}
