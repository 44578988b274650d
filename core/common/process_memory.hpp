#pragma once
// Resident memory of a process, read from /proc/<pid>/status (Linux).

namespace stiction {

// A memory field of /proc/<pid>/status ("VmRSS", "VmHWM", ...) in MB; pid 0 = this process;
// 0 when the file or the field cannot be read.
double proc_status_mb(int pid, const char* field);
// This process's resident memory now (VmRSS) and its peak so far (VmHWM), in MB.
inline double resident_mb() { return proc_status_mb(0, "VmRSS"); }
inline double peak_resident_mb() { return proc_status_mb(0, "VmHWM"); }

}  // namespace stiction
