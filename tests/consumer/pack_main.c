/* The installed runtime pack reader (gusuku::pack_loader, in the runtime component): a folder that holds no pack
 * is refused with the C API's code and a message naming the file it looked for. */
#include <stdio.h>
#include <string.h>

#include <gusuku/pack_loader/gusuku_pack_loader.h>

int main(void) {
    gusuku_bakeset* bake_set = NULL;
    const gusuku_result result = gusuku_bakeset_load_pack("/nonexistent/gusuku/bakeset", &bake_set);
    printf("consumer pack: %s: %s\n", gusuku_result_name(result), gusuku_last_error_message());
    return result == GUSUKU_ERROR_INVALID_BAKE_SET && bake_set == NULL &&
                   strstr(gusuku_last_error_message(), "manifest") != NULL
               ? 0
               : 1;
}
