// if/else inside a comprehension.
// expect echo: ECHO: ["s", "s", "b", "b"]
echo([for (i = [0:3]) if (i < 2) "s" else "b"]);
