// Seed 002's way of making a part: primitives with parameters, combined by set
// operations. A hexagonal prism (a cylinder with six sides), a cone standing on it,
// and a cylindrical bore through both.
$fn = 48;

difference() {
  union() {
    cylinder(h = 20, r = 15, $fn = 6);              // the prism
    translate([0, 0, 20]) cylinder(h = 12, r1 = 12, r2 = 4);  // the cone
  }
  translate([0, 0, -1]) cylinder(h = 34, r = 3);    // the bore
}
