// The C-style for of list comprehensions, with two loop variables.
// expect echo: ECHO: [1, 2, 4, 8, 16]
echo([for (i = 0, j = 1; i < 5; i = i + 1, j = j * 2) j]);
