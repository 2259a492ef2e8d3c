/* anitet's partitions from C: mesh the examples' sphere, cut it into 4 parts with one ghost
 * layer, print the partition's figures and each part's counts, then do what a solver's halo
 * exchange does, here between the parts of one process: each part fills the vertices it owns,
 * sends SEND[q] to each neighbour q, and writes what q sent into RECV[q]. Both sides list the
 * same global ids in the same order, so no ids travel. Exit code 0 when every ghost vertex got
 * its owner's value. docs/partitions.md walks through it.
 *
 *   partition_sphere */
#include <stdio.h>
#include <stdlib.h>

#include "anitet.h"

#include "sphere_surface.h"

enum { PARTS = 4 };

static int fail(const char* what, int code) {
  fprintf(stderr, "%s: %s (%s)\n", what, anitet_last_error_message(), anitet_error_name(code));
  return 1;
}

/* A lent array of the part (no copy; 0-based ids; valid while the partition lives). */
static const void* array(const anitet_part* part, int32_t which, int64_t* count) {
  const void* data = NULL;
  anitet_part_get_array(part, which, &data, count, NULL);
  return data;
}

/* What the owner of a vertex gives it: a value only the owner can compute. */
static double owner_value(int32_t owner, int64_t global_id) { return 1e6 * owner + (double)global_id; }

int main(void) {
  static double xyz[3 * SPHERE_NPOINTS];
  static int32_t tri[3 * SPHERE_NTRI], patch[SPHERE_NTRI];
  anitet_surface* surface = NULL;
  anitet_mesh* mesh = NULL;
  anitet_partition* partition = NULL;
  anitet_partition_options options = ANITET_PARTITION_OPTIONS_INIT;
  anitet_partition_info info = ANITET_PARTITION_INFO_INIT;
  const anitet_part* parts[PARTS];
  double* field[PARTS];
  int rc, p, wrong = 0;

  sphere_build(xyz, tri, patch);
  if ((rc = anitet_surface_create(xyz, SPHERE_NPOINTS, tri, SPHERE_NTRI, patch, 0, &surface))) return fail("surface", rc);
  if ((rc = anitet_mesher_run(surface, NULL, NULL, &mesh))) return fail("mesher", rc);

  options.ghost_layers = 1;
  if ((rc = anitet_mesh_partition(mesh, PARTS, &options, &partition))) return fail("partition", rc);
  anitet_partition_get_info(partition, &info);
  printf("%lld tets in %d parts: edge cut %lld faces, %lld interface vertices, imbalance %.2f%%\n",
         (long long)info.num_tets, info.num_parts, (long long)info.edge_cut, (long long)info.interface_vertices,
         100 * info.imbalance);

  /* Each part: counts, and its vertex field with the own vertices filled, the others unknown. */
  for (p = 0; p < PARTS; ++p) {
    int64_t nv, nov, nt, nto, nb, nob, n, i;
    int32_t neighbours;
    const int64_t* global;
    anitet_partition_get_part(partition, p, &parts[p]);
    anitet_part_get_counts(parts[p], &nv, &nov, &nt, &nto, &nb, &nob);
    anitet_part_get_index(parts[p], NULL, NULL, &neighbours, NULL);
    printf("part %d: %lld vertices (%lld own), %lld tets (%lld own), %lld boundary triangles (%lld own), "
           "%d neighbours\n", p, (long long)nv, (long long)nov, (long long)nt, (long long)nto, (long long)nb,
           (long long)nob, neighbours);
    global = array(parts[p], ANITET_PART_VERTEX_GLOBAL_IDS, &n);
    field[p] = malloc((size_t)nv * sizeof *field[p]);
    for (i = 0; i < nv; ++i) field[p][i] = i < nov ? owner_value(p, global[i]) : -1.0; /* own vertices first */
  }

  /* The halo update: part p's SEND list towards q is q's RECV list from p, item for item. */
  for (p = 0; p < PARTS; ++p) {
    int64_t n_nb, c, k;
    const int32_t* neighbours = array(parts[p], ANITET_PART_NEIGHBOURS, &n_nb);
    const int64_t* send_at = array(parts[p], ANITET_PART_VERTEX_SEND_OFFSETS, &c);
    const int32_t* send = array(parts[p], ANITET_PART_VERTEX_SEND, &c);
    for (k = 0; k < n_nb; ++k) {
      const int32_t q = neighbours[k];
      int64_t q_nb, back, j;
      const int32_t* q_neighbours = array(parts[q], ANITET_PART_NEIGHBOURS, &q_nb);
      const int64_t* recv_at = array(parts[q], ANITET_PART_VERTEX_RECV_OFFSETS, &c);
      const int32_t* recv = array(parts[q], ANITET_PART_VERTEX_RECV, &c);
      for (back = 0; q_neighbours[back] != p; ++back) {
      }
      /* (With MPI: MPI_Isend of field[p][send[...]] to rank q, MPI_Irecv on q from rank p.) */
      for (j = 0; j < send_at[k + 1] - send_at[k]; ++j)
        field[q][recv[recv_at[back] + j]] = field[p][send[send_at[k] + j]];
    }
  }

  /* Every local vertex of every part now holds its owner's value. */
  for (p = 0; p < PARTS; ++p) {
    int64_t n, i;
    const int64_t* global = array(parts[p], ANITET_PART_VERTEX_GLOBAL_IDS, &n);
    const int32_t* owner = array(parts[p], ANITET_PART_VERTEX_OWNERS, &n);
    for (i = 0; i < n; ++i) wrong += field[p][i] != owner_value(owner[i], global[i]);
    free(field[p]);
  }
  printf("halo update: %d vertices without their owner's value\n", wrong);

  anitet_partition_destroy(partition); /* frees the parts it lent */
  anitet_mesh_destroy(mesh);
  anitet_surface_destroy(surface);
  return wrong != 0;
}
