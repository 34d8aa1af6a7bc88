/* The installed loader: a folder that holds no bake set is refused with the C API's code and a message. */
#include <stdio.h>
#include <string.h>

#include <gusuku/loader/gusuku_loader.h>

int main(void) {
    gusuku_bakeset* bake_set = NULL;
    const gusuku_result result = gusuku_bakeset_load("/nonexistent/gusuku/bakeset", &bake_set);
    printf("consumer loader: %s: %s\n", gusuku_result_name(result), gusuku_last_error_message());
    return result == GUSUKU_ERROR_INVALID_BAKE_SET && bake_set == NULL &&
                   strstr(gusuku_last_error_message(), "manifest.json") != NULL
               ? 0
               : 1;
}
