// Placeholder entry point; the real CLI replaces it.
int main() { return 0; }
