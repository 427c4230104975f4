// projection(cut = true) through slanted faces: the surface of heights 0.3 2.9 / 0.3 2.9
// is the plane z = 0.3 + 2.6 x over the unit square; lowered by 1.1 it meets z = 0
// along x = 0.8 / 2.6 = 4/13, where its slanted edges cross the plane at points whose
// computed z is not exactly 0. The section is (9/13) x 1.
// expect volume: 0.6923076923076923
// expect bbox: [0.3076923076923077, 0, 0] [1, 1, 1]
linear_extrude(1) projection(cut = true) translate([0, 0, -1.1]) surface("data/ramp.dat");
