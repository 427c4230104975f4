// A 4-cube minus a hollow 2-cube shell: 64 - 7, the 1-cube left inside a cavity.
// expect volume: 57
// expect counts: volumes=2
difference() {
  cube(4, center = true);
  difference() { cube(2, center = true); cube(1, center = true); }
}
