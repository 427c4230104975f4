// Strings: str() of mixed values, UTF-8 length and indexing, chr and ord.
// expect echo: ECHO: "a1[1, 2]", 5, "Hi", 65, "b", "é", "x = 2.5"
echo(str("a", 1, [1, 2]), len("héllo"), chr(72, 105), ord("A"), "abc"[1], "héllo"[1],
     str("x = ", 2.5));
