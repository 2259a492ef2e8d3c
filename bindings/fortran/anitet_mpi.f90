! Fortran module `anitet_mpi`: include/anitet_mpi.h through mpi_f08's communicator handle
! (comm%MPI_VAL, passed to the C functions anitet_*_f), in a module of its own so that module
! `anitet` stays MPI-free. Link libanitet_mpi and MPI's Fortran library (target
! anitet_fortran_mpi). tests/fortran/check_interfaces.cmake checks it against anitet_mpi.h.
module anitet_mpi
  use, intrinsic :: iso_c_binding
  use mpi_f08, only: MPI_Comm
  use anitet, only: anitet_partition_options_t
  implicit none
  private

  ! ---- constants (equal to anitet_mpi.h's macros) ----------------------------------------------
  integer(c_int32_t), parameter, public :: ANITET_MPI_EXCHANGE_TAG = 24942
  integer(c_int32_t), parameter, public :: ANITET_FIELD_ON_VERTICES = 0
  integer(c_int32_t), parameter, public :: ANITET_FIELD_ON_TETS = 1

  ! ---- raw C interfaces (the Fortran-handle variants; MPI_Fint is a C int) ---------------------
  public :: c_anitet_mesh_scatter_f, c_anitet_part_exchange_f

  interface
    integer(c_int) function c_anitet_mesh_scatter_f(mesh, comm, root, options, local) &
        bind(c, name="anitet_mesh_scatter_f")
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: mesh     ! read on the root only; c_null_ptr elsewhere
      integer(c_int), value :: comm  ! comm%MPI_VAL
      integer(c_int32_t), value :: root
      type(c_ptr), value :: options  ! const anitet_partition_options*, may be c_null_ptr
      type(c_ptr), intent(out) :: local
    end function

    integer(c_int) function c_anitet_part_exchange_f(part, comm, where, values, components) &
        bind(c, name="anitet_part_exchange_f")
      import :: c_int, c_int32_t, c_double, c_ptr
      type(c_ptr), value :: part
      integer(c_int), value :: comm
      integer(c_int32_t), value :: where
      real(c_double), intent(inout) :: values(*)
      integer(c_int32_t), value :: components
    end function
  end interface

  ! ---- Fortran wrappers ---------------------------------------------------------------------------
  public :: anitet_mesh_scatter, anitet_part_exchange

contains

  ! Rank r of comm gets part r of `mesh` (read on `root` only: c_null_ptr elsewhere) in `part`,
  ! its own to free with anitet_part_destroy. Collective; every rank returns the same code.
  integer function anitet_mesh_scatter(mesh, comm, root, part, options) result(rc)
    type(c_ptr), intent(in) :: mesh
    type(MPI_Comm), intent(in) :: comm
    integer, intent(in) :: root
    type(c_ptr), intent(out) :: part
    type(anitet_partition_options_t), intent(in), optional, target :: options
    if (present(options)) then
      rc = c_anitet_mesh_scatter_f(mesh, int(comm%MPI_VAL, c_int), int(root, c_int32_t), &
                                   c_loc(options), part)
    else
      rc = c_anitet_mesh_scatter_f(mesh, int(comm%MPI_VAL, c_int), int(root, c_int32_t), &
                                   c_null_ptr, part)
    end if
  end function

  ! A halo update of values(components, local vertices or tets) (where: ANITET_FIELD_ON_*):
  ! afterwards every local item holds its owner's values. Collective over the neighbours.
  integer function anitet_part_exchange(part, comm, where, values) result(rc)
    type(c_ptr), intent(in) :: part
    type(MPI_Comm), intent(in) :: comm
    integer, intent(in) :: where
    real(c_double), intent(inout), contiguous :: values(:, :)
    rc = c_anitet_part_exchange_f(part, int(comm%MPI_VAL, c_int), int(where, c_int32_t), values, &
                                  size(values, 1, c_int32_t))
  end function

end module anitet_mpi
