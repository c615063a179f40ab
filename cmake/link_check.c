/* The empty program that each folder's library of cli/ is linked into,
 * whole (CMakeLists.txt, jc_link_check_FOLDER): it links only if every
 * call of that folder's files lands in the libraries it links. */
int main(void) { return 0; }
