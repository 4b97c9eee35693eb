// A syntax error is reported with its line (3) and exit code 1.
print("not reached either: the file does not compile");
const broken = ;
