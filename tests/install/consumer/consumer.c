/* Creates a handle through the installed library and checks the ABI version it was built against. */
#include <stdio.h>
#include <structmd.h>

int main(void) {
    structmd_sim* sim = NULL;
    if (structmd_abi_version() != STRUCTMD_ABI_VERSION) {
        fprintf(stderr, "ABI %d, header %d\n", structmd_abi_version(), STRUCTMD_ABI_VERSION);
        return 1;
    }
    if (structmd_create("{\"backend\": \"cpu\"}", &sim) != STRUCTMD_OK) {
        fprintf(stderr, "%s\n", structmd_last_error(NULL));
        return 1;
    }
    structmd_destroy(sim);
    printf("structmd %s\n", structmd_version());
    return 0;
}
