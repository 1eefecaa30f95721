/* render_hash INPUT WIDTH HEIGHT: renders INPUT with the automatic camera
 * at that size and prints its image hash as the last line, the image_hash
 * that `zscan render INPUT --size WIDTHxHEIGHT --stats` prints.
 *
 * Build: cc render_hash.c $(pkg-config --cflags --libs zscan) */
#include <stdio.h>
#include <stdlib.h>

#include <zscan/zscan.h>

int main(int argc, char **argv) {
  if (argc != 4) {
    fprintf(stderr, "usage: render_hash INPUT WIDTH HEIGHT\n");
    return 2;
  }
  zs_error err = {0};
  zs_render_opts opts = {0}; /* zbuffer, flat shading, the automatic camera */
  opts.width = atoi(argv[2]);
  opts.height = atoi(argv[3]);
  zs_scene *scene = NULL;
  zs_image im = {0};
  if (zs_scene_load(argv[1], NULL, &scene, &err) ||
      zs_render(scene, &opts, &im, NULL, NULL, &err)) {
    fprintf(stderr, "render_hash: %s\n", err.msg);
    zs_scene_destroy(scene);
    return 1;
  }
  printf("%s: %d objects, %llu faces, %dx%d\n", argv[1], (int)zs_scene_objects(scene),
         (unsigned long long)zs_scene_faces(scene), im.width, im.height);
  printf("%016llx\n", (unsigned long long)zs_image_hash(&im));
  zs_image_free(&im);
  zs_scene_destroy(scene);
  return 0;
}
