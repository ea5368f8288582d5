/* How much of a PNG is drawn: png_ink FILE prints "WIDTH HEIGHT INK
 * X0 Y0 X1 Y1 COLOURS": the image size, the pixels that differ from the
 * top-left one (the background), their bounding box and how many distinct
 * colours they use (up to 1000). Exit 0 if it read the file. For the
 * plot tests: a rendered frame that is blank, or drawn in one corner, or
 * in one colour, is caught. libpng's simplified API. */
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: png_ink FILE.png\n");
        return 2;
    }
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&im, argv[1])) {
        fprintf(stderr, "png_ink: %s: %s\n", argv[1], im.message);
        return 1;
    }
    im.format = PNG_FORMAT_RGBA;
    png_bytep px = malloc(PNG_IMAGE_SIZE(im));
    if (!px || !png_image_finish_read(&im, NULL, px, 0, NULL)) {
        fprintf(stderr, "png_ink: %s: %s\n", argv[1], px ? im.message : "out of memory");
        return 1;
    }
    const unsigned w = im.width, h = im.height;
    unsigned long ink = 0;
    unsigned x0 = w, y0 = h, x1 = 0, y1 = 0, ncol = 0;
    static unsigned colours[1000];
    for (unsigned y = 0; y < h; y++)
        for (unsigned x = 0; x < w; x++) {
            const png_bytep p = px + 4 * ((size_t)y * w + x);
            if (memcmp(p, px, 4) == 0) continue;
            ink++;
            if (x < x0) x0 = x;
            if (y < y0) y0 = y;
            if (x > x1) x1 = x;
            if (y > y1) y1 = y;
            const unsigned c = (unsigned)p[0] << 24 | (unsigned)p[1] << 16 | (unsigned)p[2] << 8 | p[3];
            unsigned k = 0;
            while (k < ncol && colours[k] != c) k++;
            if (k == ncol && ncol < 1000) colours[ncol++] = c;
        }
    printf("%u %u %lu %u %u %u %u %u\n", w, h, ink, x0, y0, x1, y1, ncol);
    free(px);
    return 0;
}
