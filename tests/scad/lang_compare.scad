// Comparison and equality: strings order lexicographically; a number never equals a bool.
// expect echo: ECHO: true, true, true, false, true, false, true
echo(1 < 2, "a" < "b", [1, 2] == [1, 2], 1 == true, undef == undef, 2 <= 1, "b" >= "a");
