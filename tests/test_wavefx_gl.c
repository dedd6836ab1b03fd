/* test_wavefx_gl: being written. */
int main(void) { return 77; }
