/* The C ABI from two threads: each validates its own surface many times at once, two meshers run
 * at once and give the mesh of a lone run, and the last error message is per thread. */
#define _POSIX_C_SOURCE 200112L
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

#include "capi_test_util.h"
#include "sphere_surface.h"

enum { kRounds = 30 };

struct worker {
  int index;
  pthread_barrier_t* barrier;
  int failures;      /* calls whose result differed from the expected one */
  int message_kept;  /* 1 when this thread's own error message survived the other's calls */
};

static void* validate_loop(void* arg) {
  struct worker* w = (struct worker*)arg;
  anitet_surface* s = NULL;
  int round;
  /* Thread 0 gets an open cube (an error), thread 1 a closed one. */
  const int64_t ntri = w->index == 0 ? 11 : 12;
  const int expected = w->index == 0 ? ANITET_ERR_OPEN_BOUNDARY : ANITET_OK;
  if (anitet_surface_create(kCubeXyz, 8, kCubeTri, ntri, NULL, 0, &s) != ANITET_OK) {
    w->failures++;
    return NULL;
  }
  pthread_barrier_wait(w->barrier);
  for (round = 0; round < kRounds; ++round) {
    if (anitet_surface_validate(s, NULL) != expected) w->failures++;
  }
  /* Thread 0 sets an error and keeps it while thread 1 succeeds; then both check. */
  if (w->index == 0) {
    anitet_surface_get_points(NULL, NULL, 0);
  }
  pthread_barrier_wait(w->barrier);
  if (w->index == 1) {
    if (anitet_surface_get_counts(s, NULL, NULL) != ANITET_OK) w->failures++;
  }
  pthread_barrier_wait(w->barrier);
  if (w->index == 0) {
    w->message_kept = strstr(anitet_last_error_message(), "surface is NULL") != NULL;
  } else {
    w->message_kept = anitet_last_error_message()[0] == '\0';
  }
  anitet_surface_destroy(s);
  return NULL;
}

static void test_two_threads_validate_concurrently(void** state) {
  pthread_barrier_t barrier;
  pthread_t threads[2];
  struct worker workers[2];
  int i;
  (void)state;
  assert_int_equal(pthread_barrier_init(&barrier, NULL, 2), 0);
  for (i = 0; i < 2; ++i) {
    memset(&workers[i], 0, sizeof workers[i]);
    workers[i].index = i;
    workers[i].barrier = &barrier;
    assert_int_equal(pthread_create(&threads[i], NULL, validate_loop, &workers[i]), 0);
  }
  for (i = 0; i < 2; ++i) assert_int_equal(pthread_join(threads[i], NULL), 0);
  pthread_barrier_destroy(&barrier);
  for (i = 0; i < 2; ++i) {
    assert_int_equal(workers[i].failures, 0);
    assert_int_equal(workers[i].message_kept, 1);
  }
}

struct mesher_worker {
  const anitet_surface* surface;
  pthread_barrier_t* barrier;
  int rounds;
  int rc;             /* first failing code, ANITET_OK otherwise */
  int64_t tets[4];    /* tets of each round */
};

static void* mesh_loop(void* arg) {
  struct mesher_worker* w = (struct mesher_worker*)arg;
  int round;
  pthread_barrier_wait(w->barrier);
  for (round = 0; round < w->rounds; ++round) {
    anitet_mesh* m = NULL;
    const int rc = anitet_mesher_run(w->surface, NULL, NULL, &m);
    if (rc != ANITET_OK) {
      w->rc = rc;
      return NULL;
    }
    anitet_mesh_get_counts(m, NULL, &w->tets[round], NULL);
    anitet_mesh_destroy(m);
  }
  return NULL;
}

static void test_two_meshers_in_two_threads(void** state) {
  static double xyz[3 * SPHERE_NPOINTS];
  static int32_t tri[3 * SPHERE_NTRI], patch[SPHERE_NTRI];
  pthread_barrier_t barrier;
  pthread_t threads[2];
  struct mesher_worker workers[2];
  anitet_surface* surfaces[2] = {NULL, NULL};
  anitet_mesh* alone = NULL;
  int64_t tets_alone = 0;
  int i, round;
  (void)state;
  sphere_build(xyz, tri, patch);
  for (i = 0; i < 2; ++i) {
    assert_int_equal(anitet_surface_create(xyz, SPHERE_NPOINTS, tri, SPHERE_NTRI, patch, 0, &surfaces[i]),
                     ANITET_OK);
  }
  assert_int_equal(anitet_mesher_run(surfaces[0], NULL, NULL, &alone), ANITET_OK);
  assert_int_equal(anitet_mesh_get_counts(alone, NULL, &tets_alone, NULL), ANITET_OK);
  anitet_mesh_destroy(alone);
  assert_int_equal(pthread_barrier_init(&barrier, NULL, 2), 0);
  for (i = 0; i < 2; ++i) {
    memset(&workers[i], 0, sizeof workers[i]);
    workers[i].surface = surfaces[i];
    workers[i].barrier = &barrier;
    workers[i].rounds = 4;
    assert_int_equal(pthread_create(&threads[i], NULL, mesh_loop, &workers[i]), 0);
  }
  for (i = 0; i < 2; ++i) assert_int_equal(pthread_join(threads[i], NULL), 0);
  pthread_barrier_destroy(&barrier);
  for (i = 0; i < 2; ++i) {
    assert_int_equal(workers[i].rc, ANITET_OK);
    for (round = 0; round < 4; ++round) assert_int_equal(workers[i].tets[round], tets_alone);
    anitet_surface_destroy(surfaces[i]);
  }
}

static void* set_error_then_return(void* arg) {
  (void)arg;
  anitet_mesh_get_counts(NULL, NULL, NULL, NULL);
  return NULL;
}

static void test_last_error_is_thread_local(void** state) {
  pthread_t t;
  (void)state;
  assert_int_equal(anitet_options_init(NULL, 1), ANITET_ERR_INVALID_ARGUMENT);
  assert_int_equal(pthread_create(&t, NULL, set_error_then_return, NULL), 0);
  assert_int_equal(pthread_join(t, NULL), 0);
  /* The other thread's "mesh is NULL" did not replace this thread's message. */
  assert_non_null(strstr(anitet_last_error_message(), "options is NULL"));
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_two_threads_validate_concurrently),
      cmocka_unit_test(test_two_meshers_in_two_threads),
      cmocka_unit_test(test_last_error_is_thread_local),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
