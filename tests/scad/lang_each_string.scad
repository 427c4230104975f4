// each over a string gives its characters; for over a number runs once.
// expect echo: ECHO: ["a", "b", "c"], [5]
echo([each "abc"], [for (i = 5) i]);
