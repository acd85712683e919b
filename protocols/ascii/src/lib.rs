//! HIMC Native ASCII (3999) and User ASCII (4000) front-ends (ARCHITECTURE §5). Filled by the ASCII issue.
