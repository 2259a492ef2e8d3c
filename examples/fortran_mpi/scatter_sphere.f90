! anitet from an MPI Fortran solver: rank 0 meshes the examples' sphere through the C ABI,
! anitet_mesh_scatter gives every rank its part (own tets, one layer of ghost tets, global ids,
! owners, halo lists), each rank sums the volumes of its own tets and MPI_Allreduce adds them up
! (equal to the whole mesh's volume to 1e-12), then a ghost exchange of a vertex field by hand,
! with plain MPI over the part's send/recv lists (no negotiation: both sides list the same global
! ids in the same order), gives every rank the owners' values; anitet_part_exchange does the same
! for a second field. Exit code 0 when every check holds on every rank.
!
!   mpirun -np 4 scatter_sphere
program scatter_sphere
  use, intrinsic :: iso_c_binding
  use mpi_f08
  use anitet
  use anitet_mpi
  use sphere_surface
  implicit none

  type(c_ptr) :: mesh, part
  type(anitet_partition_options_t) :: options
  integer :: rank, ranks, failures, all_failures
  real(c_double) :: whole_volume, my_volume, volume_sum
  integer(c_int64_t) :: whole_tets, my_tets, tets_sum

  call MPI_Init()
  call MPI_Comm_rank(MPI_COMM_WORLD, rank)
  call MPI_Comm_size(MPI_COMM_WORLD, ranks)
  failures = 0

  ! Rank 0 meshes; the other ranks hold no mesh.
  mesh = c_null_ptr
  whole_volume = 0
  whole_tets = 0
  if (rank == 0) then
    call mesh_the_sphere(mesh)
    call whole_mesh_figures(mesh, whole_volume, whole_tets)
  end if
  call MPI_Bcast(whole_volume, 1, MPI_DOUBLE_PRECISION, 0, MPI_COMM_WORLD)
  call MPI_Bcast(whole_tets, 1, MPI_INTEGER8, 0, MPI_COMM_WORLD)

  call check(anitet_partition_options_init(options) == ANITET_OK, "partition options")
  options%ghost_layers = 1
  call check(anitet_mesh_scatter(mesh, MPI_COMM_WORLD, 0, part, options) == ANITET_OK, "scatter")
  if (rank == 0) call anitet_mesh_destroy(mesh)  ! each rank has its part now

  ! Each rank: the volume of its own tets; together, the whole mesh.
  call own_volume(part, my_volume, my_tets)
  call MPI_Allreduce(my_volume, volume_sum, 1, MPI_DOUBLE_PRECISION, MPI_SUM, MPI_COMM_WORLD)
  call MPI_Allreduce(my_tets, tets_sum, 1, MPI_INTEGER8, MPI_SUM, MPI_COMM_WORLD)
  call check(tets_sum == whole_tets, "the own tets of all ranks are the mesh's tets")
  call check(abs(volume_sum - whole_volume) <= 1d-12 * whole_volume, "volumes add up to 1e-12")

  call exchange_by_hand(part)
  call exchange_by_library(part)

  call MPI_Allreduce(failures, all_failures, 1, MPI_INTEGER, MPI_SUM, MPI_COMM_WORLD)
  if (rank == 0) then
    print '(a, i0, a, i0, a)', "ranks: ", ranks, ", mesh: ", whole_tets, " tets"
    print '(a, es23.16, a, es23.16, a, es9.2)', "sum of own volumes ", volume_sum, &
          ", whole volume ", whole_volume, ", difference ", abs(volume_sum - whole_volume)
    if (all_failures == 0) then
      print '(a)', "ghost exchange: every local vertex holds its owner's value on every rank"
    else
      print '(i0, a)', all_failures, " check(s) failed"
    end if
  end if
  call anitet_part_destroy(part)
  call MPI_Finalize()
  if (all_failures /= 0) error stop 1

contains

  subroutine check(ok, what)
    logical, intent(in) :: ok
    character(len=*), intent(in) :: what
    if (.not. ok) then
      failures = failures + 1
      print '(a, i0, a, a, a, a)', "rank ", rank, " FAILED: ", what, "; ", anitet_last_error_message()
    end if
  end subroutine

  subroutine mesh_the_sphere(m)
    type(c_ptr), intent(out) :: m
    real(c_double) :: xyz(3, SPHERE_NPOINTS)
    integer(c_int32_t) :: tri(3, SPHERE_NTRI), patch(SPHERE_NTRI)
    type(c_ptr) :: surface
    type(anitet_options_t) :: o
    call sphere_build(xyz, tri, patch)
    call check(anitet_surface_create(xyz, tri, surface, patch) == ANITET_OK, "surface")
    call check(anitet_options_init(o) == ANITET_OK, "options")
    o%size_scale = 0.5d0  ! twice as fine as the default: about 6,000 tets
    call check(anitet_mesher_run(surface, m, options=o) == ANITET_OK, "mesher")
    call anitet_surface_destroy(surface)
  end subroutine

  real(c_double) function tet_volume(xyz, t)
    real(c_double), intent(in) :: xyz(:, :)
    integer(c_int32_t), intent(in) :: t(4)
    real(c_double) :: u(3), v(3), w(3)
    u = xyz(:, t(2)) - xyz(:, t(1))
    v = xyz(:, t(3)) - xyz(:, t(1))
    w = xyz(:, t(4)) - xyz(:, t(1))
    tet_volume = (u(1) * (v(2) * w(3) - v(3) * w(2)) - u(2) * (v(1) * w(3) - v(3) * w(1)) + &
                  u(3) * (v(1) * w(2) - v(2) * w(1))) / 6
  end function

  subroutine whole_mesh_figures(m, volume, tets)
    type(c_ptr), intent(in) :: m
    real(c_double), intent(out) :: volume
    integer(c_int64_t), intent(out) :: tets
    real(c_double), allocatable :: xyz(:, :)
    integer(c_int32_t), allocatable :: t(:, :)
    integer(c_int64_t) :: i
    call check(anitet_mesh_get_points(m, xyz) == ANITET_OK, "points")
    call check(anitet_mesh_get_tets(m, t) == ANITET_OK, "tets")
    tets = size(t, 2, c_int64_t)
    volume = 0
    do i = 1, tets
      volume = volume + tet_volume(xyz, t(:, i))
    end do
  end subroutine

  subroutine own_volume(p, volume, tets)
    type(c_ptr), intent(in) :: p
    real(c_double), intent(out) :: volume
    integer(c_int64_t), intent(out) :: tets
    real(c_double), allocatable :: xyz(:, :)
    integer(c_int32_t), allocatable :: t(:, :)
    integer(c_int64_t) :: nv, nov, nt, nb, nob, i
    call check(anitet_part_get_counts(p, nv, nov, nt, tets, nb, nob) == ANITET_OK, "part counts")
    call check(anitet_part_get_points(p, xyz) == ANITET_OK, "part points")
    call check(anitet_part_get_tets(p, t) == ANITET_OK, "part tets")  ! 1-based local ids
    volume = 0
    do i = 1, tets  ! own tets come first
      volume = volume + tet_volume(xyz, t(:, i))
    end do
  end subroutine

  ! The value the owner of a vertex gives it: only the owner knows its rank is the owner's.
  real(c_double) function owner_value(global_id)
    integer(c_int64_t), intent(in) :: global_id
    owner_value = 1000000d0 * rank + real(global_id, c_double)
  end function

  ! A halo update with plain MPI: send the values at SEND(q), receive into RECV(q), per neighbour.
  subroutine exchange_by_hand(p)
    type(c_ptr), intent(in) :: p
    integer(c_int64_t), allocatable :: ids(:), so(:), ro(:)
    integer(c_int32_t), allocatable :: owners(:), neighbours(:), si(:), ri(:)
    real(c_double), allocatable :: field(:), sendbuf(:), recvbuf(:)
    type(MPI_Request), allocatable :: requests(:)
    integer(c_int64_t) :: nv, nov, nt, nto, nb, nob, k
    integer :: q, n
    call check(anitet_part_get_counts(p, nv, nov, nt, nto, nb, nob) == ANITET_OK, "counts")
    call check(anitet_part_get_vertex_global_ids(p, ids) == ANITET_OK, "vertex ids")
    call check(anitet_part_get_vertex_owners(p, owners) == ANITET_OK, "vertex owners")
    call check(anitet_part_get_neighbours(p, neighbours) == ANITET_OK, "neighbours")
    call check(anitet_part_get_halo(p, ANITET_HALO_VERTEX_SEND, so, si) == ANITET_OK, "send list")
    call check(anitet_part_get_halo(p, ANITET_HALO_VERTEX_RECV, ro, ri) == ANITET_OK, "recv list")
    allocate(field(nv))
    field = -1d0
    do k = 1, nov  ! own vertices first
      field(k) = owner_value(ids(k))
    end do
    n = size(neighbours)
    allocate(sendbuf(size(si)), recvbuf(size(ri)), requests(2 * n))
    sendbuf = field(si)
    do q = 1, n  ! offsets are 1-based: items(so(q) : so(q+1) - 1) go to neighbours(q)
      call MPI_Irecv(recvbuf(ro(q):), int(ro(q + 1) - ro(q)), MPI_DOUBLE_PRECISION, &
                     int(neighbours(q)), 7, MPI_COMM_WORLD, requests(2 * q - 1))
      call MPI_Isend(sendbuf(so(q):), int(so(q + 1) - so(q)), MPI_DOUBLE_PRECISION, &
                     int(neighbours(q)), 7, MPI_COMM_WORLD, requests(2 * q))
    end do
    call MPI_Waitall(2 * n, requests, MPI_STATUSES_IGNORE)
    field(ri) = recvbuf
    do k = 1, nv
      call check(field(k) == 1000000d0 * owners(k) + real(ids(k), c_double), &
                 "a vertex holds its owner's value after the exchange by hand")
    end do
  end subroutine

  ! The same with the library's halo update, on a field of two components.
  subroutine exchange_by_library(p)
    type(c_ptr), intent(in) :: p
    integer(c_int64_t), allocatable :: ids(:)
    integer(c_int32_t), allocatable :: owners(:)
    real(c_double), allocatable :: field(:, :)
    integer(c_int64_t) :: nv, nov, nt, nto, nb, nob, k
    call check(anitet_part_get_counts(p, nv, nov, nt, nto, nb, nob) == ANITET_OK, "counts")
    call check(anitet_part_get_vertex_global_ids(p, ids) == ANITET_OK, "vertex ids")
    call check(anitet_part_get_vertex_owners(p, owners) == ANITET_OK, "vertex owners")
    allocate(field(2, nv))
    field = -1d0
    do k = 1, nov
      field(:, k) = [owner_value(ids(k)), real(rank, c_double)]
    end do
    call check(anitet_part_exchange(p, MPI_COMM_WORLD, ANITET_FIELD_ON_VERTICES, field) == ANITET_OK, &
               "anitet_part_exchange")
    do k = 1, nv
      call check(field(1, k) == 1000000d0 * owners(k) + real(ids(k), c_double) .and. &
                 field(2, k) == owners(k), "a vertex holds its owner's values after anitet_part_exchange")
    end do
  end subroutine

end program scatter_sphere
