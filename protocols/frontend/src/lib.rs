//! The front-end kit: what every protocol front-end of mcemu shares, so that a new front-end
//! writes only its codec and its service (ARCHITECTURE §5).
