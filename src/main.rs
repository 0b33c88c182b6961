fn main() {
    println!("robocal");
}
