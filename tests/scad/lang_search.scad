// search(): characters in a string, numbers in a list, keys in a table.
// expect echo: ECHO: [0], [[0, 4], [1, 5]], [1], [1]
echo(search("a", "abcdabcd"), search("ab", "abcdabcd", 0), search(3, [1, 3, 3]),
     search("b", [["a", 1], ["b", 2]]));
