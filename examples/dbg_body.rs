fn main() {
    let path = std::env::args().nth(1).unwrap();
    let mesh = sweepffd::mesh::Mesh::load(std::path::Path::new(&path)).unwrap();
    let body = sweepffd::fit::body::Body::new(&mesh);
    let mut pairs: Vec<[u32; 2]> = body.bridges.iter().map(|e| [e[0], e[1]]).collect();
    pairs.sort();
    println!("bridges {:?}", pairs);
    for l in &body.leaves {
        println!("leaf {:?} touching {:?}", l.vertices, l.touching);
    }
}
