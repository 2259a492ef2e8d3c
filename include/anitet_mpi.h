/**
 * @file anitet_mpi.h
 * MPI hand-off of anitet's partitions (libanitet_mpi, built when MPI is found; libanitet itself
 * stays MPI-free). C99; also valid C++. The conventions are anitet.h's: int error codes,
 * anitet_last_error_message() for the message, versioned options, index_base for ids.
 *
 * Every function here is collective over `comm`: every rank calls it, with the same root and
 * part count, or the ranks wait for one another. An error on the root (a bad mesh or options)
 * reaches every rank: all return the same code, the others with a message naming the root's.
 * Argument errors a rank can see alone (a NULL out pointer, a root outside the communicator)
 * are returned at once on that rank: give every rank the same arguments.
 *
 * Each rank's part is an anitet_part (anitet.h, "Partitions"): its own tets and vertices, the
 * ghost layers, global ids, owners and the halo lists, read with the anitet_part_get_* functions
 * and freed with anitet_part_destroy. A part names no other rank's memory and no root, so a
 * distributed mesher can build one on every rank without gathering the mesh anywhere.
 */
#ifndef ANITET_MPI_H
#define ANITET_MPI_H

#include <mpi.h>
#include <stdint.h>

#include "anitet.h"

#ifdef __cplusplus
extern "C" {
#endif

/** The MPI tag of anitet_part_exchange's messages on the caller's communicator: have no other
 * message with this tag in flight on it during the call. */
#define ANITET_MPI_EXCHANGE_TAG 24942

/* Where a field of anitet_part_exchange lives. */
#define ANITET_FIELD_ON_VERTICES 0 /**< one value set per local vertex */
#define ANITET_FIELD_ON_TETS 1     /**< one value set per local tet */

/** Partitions `mesh` on the root into as many parts as `comm` has ranks (anitet_mesh_partition
 * with `options`, NULL for the defaults) and sends rank r part r: *local is the calling rank's
 * part, the caller's to free with anitet_part_destroy (NULL after any error). `mesh` and
 * `options` are read on the root only (other ranks may pass NULL). The parts travel as the bytes
 * of anitet_part_serialize, point to point from the root, on a duplicate of `comm` (no message
 * of the caller's can be taken for one of them).
 * Errors (on every rank): INVALID_ARGUMENT (NULL local; root outside comm; on the root: NULL
 * mesh, more ranks than tets, bad options), anitet_mesh_partition's other codes, PARSE (bytes
 * that arrived damaged), INTERNAL (an MPI call failed: the message has MPI's text),
 * OUT_OF_MEMORY. */
ANITET_API int anitet_mesh_scatter(const anitet_mesh* mesh, MPI_Comm comm, int32_t root,
                                   const anitet_partition_options* options, anitet_part** local);
/** anitet_mesh_scatter with a Fortran communicator handle: `comm` is mpi_f08's comm%MPI_VAL, or
 * the integer of the `mpi` module (converted with MPI_Comm_f2c). */
ANITET_API int anitet_mesh_scatter_f(const anitet_mesh* mesh, MPI_Fint comm, int32_t root,
                                     const anitet_partition_options* options, anitet_part** local);

/** A halo update: every rank sends the values of its own items that a neighbour holds
 * (ANITET_HALO_*_SEND) and writes what each neighbour sent into the items it owns
 * (ANITET_HALO_*_RECV), so that afterwards every local vertex (tet) holds its owner's values.
 * `values` has `components` doubles per local vertex (where == ANITET_FIELD_ON_VERTICES) or per
 * local tet (ANITET_FIELD_ON_TETS), in the part's local order. The part must be this rank's:
 * its index the rank in `comm` and its part count the size of `comm`. Collective over the
 * neighbours (every rank calls it), on `comm` itself (no duplicate: a solver calls it every
 * step) with the tag ANITET_MPI_EXCHANGE_TAG; an MPI failure goes to comm's error handler
 * (MPI's default aborts), or is returned as INTERNAL when that handler returns. Errors: INVALID_ARGUMENT (NULL part or values, components
 * < 1, an unknown `where`, a part that is not this rank's), INTERNAL (an MPI call failed),
 * OUT_OF_MEMORY. */
ANITET_API int anitet_part_exchange(const anitet_part* part, MPI_Comm comm, int32_t where,
                                    double* values, int32_t components);
/** anitet_part_exchange with a Fortran communicator handle (as anitet_mesh_scatter_f). */
ANITET_API int anitet_part_exchange_f(const anitet_part* part, MPI_Fint comm, int32_t where,
                                      double* values, int32_t components);

#ifdef __cplusplus
}
#endif

#endif /**< ANITET_MPI_H */
