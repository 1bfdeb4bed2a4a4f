fn main() {
    println!("aster");
}
