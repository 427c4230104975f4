// A build plate of 12 drilled blocks (a file with many parts): each block is one part
// of the build, so that after an edit of one block a rebuild from the cache
// (`cellforge build --cache DIR`) rebuilds that block only.
rows = 3;
columns = 4;
pitch = 30;
holes = 4;
hole_r = 1.5;

module block(hole_r) {
  difference() {
    cube([20, 20, 10]);
    for (k = [0 : holes - 1])
      translate([4 + k * 4, 10, -1]) cylinder(h = 12, r = hole_r, $fn = 32);
  }
}

for (i = [0 : columns - 1], j = [0 : rows - 1]) translate([i * pitch, j * pitch, 0]) block(hole_r);
translate([0, -pitch, 0]) difference() {
  cube([20, 20, 10]);
  translate([10, 10, -1]) cylinder(h = 12, r = 5, $fn = 48);
}
