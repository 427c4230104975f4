// Two cubes sharing only an edge: one valid non-manifold result.
// expect volume: 2
// expect valid
cube(1);
translate([1, 1, 0]) cube(1);
