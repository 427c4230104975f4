// The hull of two faceted spheres: a capsule.
// Each sphere has 8 rings; its widest is at polar angle 78.75 degrees, radius sin(78.75).
// expect bbox: [-0.9807852804032304, -0.9807852804032304, -0.9807852804032304] [4.98078528040323, 0.9807852804032304, 0.9807852804032304]
// expect valid
hull() { sphere(1, $fn = 16); translate([4, 0, 0]) sphere(1, $fn = 16); }
