"""Live machine link: GRBL-family streaming, the job journal and resume.

* :mod:`.protocol` -- reply parsing and the error/alarm texts,
* :mod:`.job`      -- what is streamed (lines, segments) and resume programs,
* :mod:`.journal`  -- the append-only record of acknowledged lines,
* :mod:`.grbl`     -- :class:`GrblLink`: greet, identify, stream, stop safely,
* :mod:`.progress` -- what status reports prove executed; the cut window.

See docs/LINK.md.
"""

from .grbl import ControllerInfo, GrblLink, LinkError, StreamResult
from .job import SendJob, job_from_file, job_from_lines, job_from_program, resume_job
from .journal import Journal, JournalState, load_journal
from .session import SendOutcome, SendSession

__all__ = ["ControllerInfo", "GrblLink", "LinkError", "StreamResult", "SendJob",
           "job_from_file", "job_from_lines", "job_from_program", "resume_job",
           "Journal", "JournalState", "load_journal", "SendOutcome", "SendSession"]
