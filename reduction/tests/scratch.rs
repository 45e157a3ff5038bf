#[test]
fn scratch() {
    let b = reduction::lin::beam::appendix_a_beam().unwrap();
    let s = reduction::lin::beam::summary(&b).unwrap();
    println!("{}", serde_json::to_string_pretty(&s).unwrap());
    let p = reduction::lin::beam::profile_study(&b).unwrap();
    println!("{:?}", p.z_simply_supported);
    for r in p.profile2.iter() { println!("{:?}", r.z); println!("{:?}", r.delta);}
    let e = reduction::lin::beam::mean_axes_study(&b, reduction::Method::ModeCondensation).unwrap();
    println!("{:?}", e.constraint_coordinates);
    println!("{:?}", e.normal_coordinates);
    println!("{:?}", e.normal_modes);
    for i in 0..10 { println!("{:?}", (0..10).map(|j| b.k[(i,j)]).collect::<Vec<_>>()); }
}
