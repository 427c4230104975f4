// children(i) and $children: the second child only.
// expect echo: ECHO: 2
// expect volume: 8
module second() { echo($children); children(1); }
second() { cube(1); cube(2); }
