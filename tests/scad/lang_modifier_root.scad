// '!' makes its subtree the whole result.
// expect volume: 8
cube(10);
!cube(2);
