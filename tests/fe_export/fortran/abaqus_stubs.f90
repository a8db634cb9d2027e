! Stand-ins for the Abaqus message utilities used by the generated routines.
subroutine stdb_abqerr(lop, string, intv, realv, charv)
  implicit none
  integer, intent(in) :: lop, intv(*)
  character(len=*), intent(in) :: string
  real(8), intent(in) :: realv(*)
  character(len=8), intent(in) :: charv(*)
  write (0, '(a,i3,2a)') 'ABQERR ', lop, ' ', trim(string)
  if (lop == -3) stop 3
end subroutine stdb_abqerr

subroutine xplb_abqerr(lop, string, intv, realv, charv)
  implicit none
  integer, intent(in) :: lop, intv(*)
  character(len=*), intent(in) :: string
  real(8), intent(in) :: realv(*)
  character(len=8), intent(in) :: charv(*)
  write (0, '(a,i3,2a)') 'ABQERR ', lop, ' ', trim(string)
  if (lop == -3) stop 3
end subroutine xplb_abqerr
