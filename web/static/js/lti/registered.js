/**
 * Dynamic registration done: the LMS closes its registration window on this message (LTI Dynamic Registration,
 * "org.imsglobal.lti.close").
 */
(window.opener || window.parent).postMessage({ subject: "org.imsglobal.lti.close" }, "*");
