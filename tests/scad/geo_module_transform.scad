// A module that places its children.
// expect bbox: [5, 0, 0] [6, 1, 1]
module place() translate([5, 0, 0]) children();
place() cube(1);
